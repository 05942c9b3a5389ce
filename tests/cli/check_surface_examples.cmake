# Runs scripts/run_surface_examples.sh into OUT_DIR (the main job's surface part) and
# fails unless it exits 0 and every random surface in surfaces/ and every study in
# studies/surfaces/ produced its HDF5 file and its figure.
file(REMOVE_RECURSE "${OUT_DIR}")
execute_process(COMMAND ${CMAKE_COMMAND} -E env STENGMC_RESULTS_DIR=${OUT_DIR} STENGMC_BINARY=${BINARY}
                        bash "${SOURCE_DIR}/scripts/run_surface_examples.sh"
                WORKING_DIRECTORY "${SOURCE_DIR}"
                RESULT_VARIABLE status
                OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "run_surface_examples.sh exited ${status}:\n${output}")
endif()
set(expected)
file(GLOB surfaces "${SOURCE_DIR}/surfaces/*.toml")
foreach(surface ${surfaces})
  file(READ "${surface}" text)
  if(text MATCHES "\nkind = \"random\"" OR text MATCHES "^kind = \"random\"")
    get_filename_component(name "${surface}" NAME_WE)
    list(APPEND expected "${name}_surface.h5" "${name}_surface.png")
  endif()
endforeach()
file(GLOB studies "${SOURCE_DIR}/studies/surfaces/*.toml")
foreach(study ${studies})
  get_filename_component(name "${study}" NAME_WE)
  list(APPEND expected "${name}.h5" "${name}.png")
endforeach()
list(LENGTH expected count)
if(count EQUAL 0)
  message(FATAL_ERROR "no random surfaces or surface studies found")
endif()
foreach(product ${expected})
  if(NOT EXISTS "${OUT_DIR}/${product}")
    message(FATAL_ERROR "missing ${OUT_DIR}/${product}\n${output}")
  endif()
endforeach()
message(STATUS "surface examples ran; ${count} files exist")
