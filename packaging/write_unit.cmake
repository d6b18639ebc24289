# Writes the systemd unit for one install prefix: the package's (/usr), a `cmake --install
# --prefix`'s, and tests/packaging's, which scores this very file with systemd-analyze.
# cmake -DUNIT_IN=<wavebenchd.service.in> -DPREFIX=<prefix> -DUNIT_OUT=<file> -P write_unit.cmake
foreach(var UNIT_IN PREFIX UNIT_OUT)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "write_unit.cmake: ${var} is not set (expected -D${var}=...)")
  endif()
endforeach()
file(READ "${UNIT_IN}" unit)
string(CONFIGURE "${unit}" unit @ONLY)  # @PREFIX@, as configure_file would
file(WRITE "${UNIT_OUT}" "${unit}")
