# Runs scripts/run_paper_studies.sh into OUT_DIR and fails unless it exits 0 and every
# study in studies/paper/ produced both its HDF5 file and its PNG figure.
file(REMOVE_RECURSE "${OUT_DIR}")
execute_process(COMMAND ${CMAKE_COMMAND} -E env STENGMC_RESULTS_DIR=${OUT_DIR} STENGMC_BINARY=${BINARY}
                        bash "${SOURCE_DIR}/scripts/run_paper_studies.sh"
                WORKING_DIRECTORY "${SOURCE_DIR}"
                RESULT_VARIABLE status
                OUTPUT_VARIABLE output ERROR_VARIABLE output)
if(NOT status EQUAL 0)
  message(FATAL_ERROR "run_paper_studies.sh exited ${status}:\n${output}")
endif()
file(GLOB studies "${SOURCE_DIR}/studies/paper/*.toml")
list(LENGTH studies count)
if(count EQUAL 0)
  message(FATAL_ERROR "no studies in ${SOURCE_DIR}/studies/paper")
endif()
foreach(study ${studies})
  get_filename_component(name "${study}" NAME_WE)
  set(expected "${name}.h5" "${name}.png")
  file(READ "${study}" text)
  if(text MATCHES "\n\\[spectrum\\]")
    list(APPEND expected "${name}_spectrum.png")
  endif()
  foreach(product ${expected})
    if(NOT EXISTS "${OUT_DIR}/${product}")
      message(FATAL_ERROR "missing ${OUT_DIR}/${product}\n${output}")
    endif()
  endforeach()
endforeach()
if(NOT EXISTS "${OUT_DIR}/fig4_comparison.png")
  message(FATAL_ERROR "missing ${OUT_DIR}/fig4_comparison.png")
endif()
message(STATUS "${count} paper studies ran; all figures exist")
