# ctest reads this after each tests/<area>'s tests are known (tests/CMakeLists.txt adds it to
# every area's TEST_INCLUDE_FILES): about the seconds the slowest tests take on CI's 2-core
# machine under `ctest -j2`. On a fresh clone ctest has no timing history and starts tests in
# index order, so the long ones could start last and leave a core idle at the end; a COST makes
# `ctest -j` start them first. Later runs use the measured times in
# Testing/Temporary/CTestCostData.txt. Names not (yet) defined when a directory includes this
# are ignored by ctest; properties of tests added with add_test() land when the next area
# includes it.
foreach(cost IN ITEMS
    "DaemonOnTheRealClock.StaticRunsInARowNeitherTripNorNeedAReset=220"
    "UnitTwinAcceptance.CalibratedAcrossProceduresPredictsOtherSpeedsAndLoadsAtTheFloor=207"
    "results_schema=47"
    "packaging_unit_sandbox_run=35"
    "UncertaintyAcceptance.TheTruthLiesInsideTheK2IntervalInAtLeast18Of20SeededRuns=31"
    "TwinDiagnosisAcceptance.AHealthyUnitRunsTwentyRevolutionsWithoutAFlag=26")
  string(REPLACE "=" ";" name_seconds "${cost}")
  list(GET name_seconds 0 name)
  list(GET name_seconds 1 seconds)
  set_tests_properties("${name}" PROPERTIES COST "${seconds}")
endforeach()
