# Every file includes toml++ through core/toml_library.hpp, which compiles its Unicode tables
# with the fix that header explains; a file including <toml++/toml.h> directly would compile
# the tables again without it (undefined behaviour, and two definitions of one inline
# function). Run: cmake -DSOURCE_DIR=<repository> -P check_toml_include.cmake
file(GLOB_RECURSE files LIST_DIRECTORIES false
     "${SOURCE_DIR}/src/*.hpp" "${SOURCE_DIR}/src/*.cpp" "${SOURCE_DIR}/python/*.hpp" "${SOURCE_DIR}/python/*.cpp"
     "${SOURCE_DIR}/tests/*.hpp" "${SOURCE_DIR}/tests/*.cpp" "${SOURCE_DIR}/bench/*.hpp" "${SOURCE_DIR}/bench/*.cpp")
set(offenders)
foreach(file IN LISTS files)
  if(file MATCHES "/src/core/toml_library\\.hpp$")
    continue()
  endif()
  file(STRINGS "${file}" lines REGEX "^[ \t]*#[ \t]*include[ \t]*[<\"]toml\\+\\+/")
  if(lines)
    list(APPEND offenders "${file}")
  endif()
endforeach()
list(LENGTH files count)
if(count LESS 50)
  message(FATAL_ERROR "found only ${count} source files under ${SOURCE_DIR}: wrong SOURCE_DIR?")
endif()
if(offenders)
  list(JOIN offenders "\n  " listed)
  message(FATAL_ERROR "include toml++ through \"core/toml_library.hpp\", not directly:\n  ${listed}")
endif()
message(STATUS "${count} files: toml++ only through core/toml_library.hpp")
