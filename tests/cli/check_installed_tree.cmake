# The installed tree stands on its own: `cmake --install` into a temporary prefix, the
# prefix moved elsewhere (so no path the build knew exists any more), then the moved
# binary runs a shipped example study and plots its output with the installed scripts,
# and the installed Python package (when built) imports and runs it too.
# Fails unless each step exits 0 and its product exists, and if the installed binary
# names the source or build tree (a compiled-in absolute path would break once moved).
# With MPI (MPIEXEC and MPI_MODULE given), the moved binary also runs an ensemble under
# mpirun, which opens the installed MPI module relative to it.
file(REMOVE_RECURSE "${WORK_DIR}")
file(MAKE_DIRECTORY "${WORK_DIR}/results")

function(run_step what)
  execute_process(COMMAND ${ARGN} WORKING_DIRECTORY "${WORK_DIR}/results"
                  RESULT_VARIABLE status OUTPUT_VARIABLE output ERROR_VARIABLE output)
  if(NOT status EQUAL 0)
    message(FATAL_ERROR "${what} exited ${status}:\n${output}")
  endif()
endfunction()

run_step("cmake --install" ${CMAKE_COMMAND} --install "${BUILD_DIR}" --prefix "${WORK_DIR}/staged")
file(RENAME "${WORK_DIR}/staged" "${WORK_DIR}/moved")
set(prefix "${WORK_DIR}/moved")

foreach(expected bin/stengmc share/stengmc/scripts/plot_run.py share/stengmc/scripts/stengmc_h5.py
                 share/stengmc/examples/studies/paper/fig2_k155.toml
                 share/stengmc/examples/surfaces/paper_four_stiffnesses.toml share/doc/stengmc/model.md
                 share/man/man1/stengmc.1 share/bash-completion/completions/stengmc share/doc/stengmc/LICENSE
                 share/doc/stengmc/CITATION.cff share/doc/stengmc/CHANGELOG.md)
  if(NOT EXISTS "${prefix}/${expected}")
    message(FATAL_ERROR "the install lacks ${expected}")
  endif()
endforeach()

# The paths as literal regular expressions (a '+' or '.' in a folder name must not match more).
string(REGEX REPLACE "([][+.*()^$?|\\])" "\\\\\\1" source_pattern "${SOURCE_DIR}")
string(REGEX REPLACE "([][+.*()^$?|\\])" "\\\\\\1" build_pattern "${BUILD_DIR}")
file(STRINGS "${prefix}/bin/stengmc" source_paths REGEX "${source_pattern}|${build_pattern}")
if(source_paths)
  message(FATAL_ERROR "the installed binary names the source or build tree: ${source_paths}")
endif()

# A fixed-list paper study (its surface file is found through ../../surfaces) and a
# random-surface study, both from the installed examples.
run_step("stengmc run (paper study)" "${prefix}/bin/stengmc" run
         "${prefix}/share/stengmc/examples/studies/paper/fig2_k155.toml" --out fig2_k155.h5)
run_step("stengmc run (random surface)" "${prefix}/bin/stengmc" run
         "${prefix}/share/stengmc/examples/studies/surfaces/gw_vb10.toml" --out gw_vb10.h5)
run_step("stengmc plot" "${prefix}/bin/stengmc" plot fig2_k155.h5 gw_vb10.h5)
foreach(product fig2_k155.h5 fig2_k155.png gw_vb10.h5 gw_vb10.png)
  if(NOT EXISTS "${WORK_DIR}/results/${product}")
    message(FATAL_ERROR "missing ${WORK_DIR}/results/${product}")
  endif()
endforeach()
# MPI: the module is installed (at the path MPI_MODULE, relative to the prefix) and found.
if(MPIEXEC)
  if(NOT EXISTS "${prefix}/${MPI_MODULE}")
    message(FATAL_ERROR "the install lacks the MPI module ${MPI_MODULE}")
  endif()
  run_step("mpirun -np 2 stengmc run (ensemble)" "${MPIEXEC}" --allow-run-as-root --oversubscribe --bind-to none -np 2
           "${prefix}/bin/stengmc" run "${prefix}/share/stengmc/examples/studies/ensembles/identifiability_quick.toml"
           -j 1 --out quick.h5)
  if(NOT EXISTS "${WORK_DIR}/results/quick.h5")
    message(FATAL_ERROR "missing ${WORK_DIR}/results/quick.h5")
  endif()
endif()
# The Python package (when built): imports from the moved tree and runs the same study.
if(PYTHON_PACKAGE_DIR)
  run_step("python3 -c 'import stengmc'" ${CMAKE_COMMAND} -E env "PYTHONPATH=${prefix}/${PYTHON_PACKAGE_DIR}"
           /usr/bin/python3 -c "import stengmc; assert stengmc.__file__.startswith('${prefix}'), stengmc.__file__; stengmc.load_study('${prefix}/share/stengmc/examples/studies/paper/fig2_k155.toml').run()")
endif()
message(STATUS "installed, moved, ran and plotted from ${prefix}")
