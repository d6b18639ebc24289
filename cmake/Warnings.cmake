# wavebench_warnings: an interface target every wavebench target links to.
add_library(wavebench_warnings INTERFACE)
target_compile_options(wavebench_warnings INTERFACE
  -Wall -Wextra -Wpedantic -Wshadow -Wnon-virtual-dtor -Wold-style-cast -Wcast-align
  -Woverloaded-virtual -Wdouble-promotion -Wformat=2 -Wimplicit-fallthrough)
if(WAVEBENCH_WERROR)
  target_compile_options(wavebench_warnings INTERFACE -Werror)
endif()
