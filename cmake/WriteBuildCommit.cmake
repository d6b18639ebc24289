# Run at every build (cmake -P): writes OUT, the commit the binaries are built from, only when
# it changed, so an unchanged tree relinks nothing. "<12 hex>" from git, "+dirty" when the
# work tree differs from it; COMMIT (a packager's -DWAVEBENCH_COMMIT) outside a git checkout;
# "unknown" when neither.
set(commit "${COMMIT}")
find_package(Git QUIET)
if(GIT_FOUND AND EXISTS "${SRC}/.git")
  execute_process(COMMAND "${GIT_EXECUTABLE}" -C "${SRC}" rev-parse --short=12 HEAD
                  OUTPUT_VARIABLE head OUTPUT_STRIP_TRAILING_WHITESPACE RESULT_VARIABLE rc
                  ERROR_QUIET)
  if(rc EQUAL 0 AND head)
    set(commit "${head}")
    execute_process(COMMAND "${GIT_EXECUTABLE}" -C "${SRC}" diff --quiet HEAD --
                    RESULT_VARIABLE dirty ERROR_QUIET)
    if(NOT dirty EQUAL 0)
      string(APPEND commit "+dirty")
    endif()
  endif()
endif()
if(NOT commit)
  set(commit "unknown")
endif()
set(text "// Written by cmake/WriteBuildCommit.cmake at build time.\n#include \"wavebench/procedures/software_version.hpp\"\n\nconst char* wavebench::procedures::software_commit() { return \"${commit}\"; }\n")
if(EXISTS "${OUT}")
  file(READ "${OUT}" old)
endif()
if(NOT old STREQUAL text)
  file(WRITE "${OUT}" "${text}")
endif()
