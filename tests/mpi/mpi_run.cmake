# `rumble` under mpirun (docs/decisions/0012-distributed-soil.md), one case per test:
#   plugins_show_mpi             `rumble plugins` names the MPI library (one rank, MPI not
#                                started) and the PETSc the FEM soil is built with
#   plugins_launched             under mpirun -n 2 it says 2 ranks, printed once (rank 0 alone)
#   same_results_on_N_ranks      the split_dashpot scenario run without mpirun and on N ranks:
#                                the soil says it is split over N ranks, every CSV is identical
#   rank_failure_stops_every_rank  split_dashpot failing on rank 1 at 20 ms: every rank stops
#                                (no hang: the test's timeout), exit code 3, rank 1's message,
#                                results up to then on disk
#   interrupt_stops_every_rank   Ctrl-C to mpirun mid-run: summary.json says "interrupted"
#   foreign_launcher_is_refused  a launcher of another MPI: a clear error before any work
#   study_spreads_runs_over_ranks  a study's runs shared out over the ranks, all completed
#   idle_ranks_are_named         a soil that is not distributed, run under mpirun -n 3: it runs,
#                                and the log says once that the other 2 ranks wait idle
set(mpirun ${MPIEXEC} --oversubscribe)
set(scenario ${SOURCE_DIR}/split_dashpot.json)
file(REMOVE_RECURSE ${WORK_DIR})
file(MAKE_DIRECTORY ${WORK_DIR})

function(rumble_run out_var code_var)
  execute_process(COMMAND ${ARGN} OUTPUT_VARIABLE out ERROR_VARIABLE err RESULT_VARIABLE code)
  set(${out_var} "${out}${err}" PARENT_SCOPE)
  set(${code_var} ${code} PARENT_SCOPE)
endfunction()

function(expect_match text regex)
  if(NOT text MATCHES "${regex}")
    message(FATAL_ERROR "expected output matching '${regex}', got:\n${text}")
  endif()
endfunction()

if(CASE STREQUAL "plugins_show_mpi")
  rumble_run(out code ${RUMBLE} plugins)
  expect_match("${out}" "MPI: Open MPI v[0-9.]+ \\(MPI [0-9.]+\\)")
  expect_match("${out}" "not launched by mpirun")
  expect_match("${out}" "built with: [^\n]*PETSc [0-9]+\\.[0-9]+")  # the FEM soil's GAMG
elseif(CASE STREQUAL "plugins_launched")
  rumble_run(out code ${mpirun} -n 2 ${RUMBLE} plugins)
  expect_match("${out}" "launched on 2 ranks")
  string(REGEX MATCHALL "plugin directory:" printed "${out}")
  list(LENGTH printed n)
  if(NOT code EQUAL 0 OR NOT n EQUAL 1)
    message(FATAL_ERROR "exit ${code}, printed ${n} times (rank 0 alone must print):\n${out}")
  endif()
elseif(CASE MATCHES "^same_results_on_([0-9])_ranks$")
  set(ranks ${CMAKE_MATCH_1})
  rumble_run(out code ${RUMBLE} run ${scenario} --output ${WORK_DIR}/one)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "the run on one process failed (${code}):\n${out}")
  endif()
  expect_match("${out}" "rank 0 of 1 ranks owns 40 footprints")
  rumble_run(out code ${mpirun} -n ${ranks} ${RUMBLE} run ${scenario}
             --output ${WORK_DIR}/many)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "the run on ${ranks} ranks failed (${code}):\n${out}")
  endif()
  math(EXPR last "${ranks} - 1")
  foreach(rank RANGE ${last})
    expect_match("${out}" "rank ${rank} of ${ranks} ranks owns")
  endforeach()
  foreach(csv footprint_displacement footprint_velocity footprint_force contact vehicles interface)
    execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${WORK_DIR}/one/${csv}.csv
                            ${WORK_DIR}/many/${csv}.csv RESULT_VARIABLE differ)
    if(NOT differ EQUAL 0)
      message(FATAL_ERROR "${csv}.csv differs between 1 process and ${ranks} ranks")
    endif()
  endforeach()
elseif(CASE STREQUAL "rank_failure_stops_every_rank")
  rumble_run(out code ${mpirun} -n 2 ${RUMBLE} run ${scenario}
             --output ${WORK_DIR}/failed --set /soil/params/fail_rank=1
             --set /soil/params/fail_at=0.02)
  if(NOT code EQUAL 3)
    message(FATAL_ERROR "expected exit code 3 (run failed), got ${code}:\n${out}")
  endif()
  expect_match("${out}" "error: MPI rank 1: soil .split_dashpot. \\(/soil\\): advance failed: split_dashpot failed on purpose at t = 0.02")
  file(STRINGS ${WORK_DIR}/failed/footprint_displacement.csv rows)
  list(LENGTH rows n)
  if(n LESS 150)
    message(FATAL_ERROR "the results up to 20 ms are not on disk (${n} rows)")
  endif()
elseif(CASE STREQUAL "interrupt_stops_every_rank")
  # mpirun, stopped (SIGTERM, as a batch system stops a job; a backgrounded shell job ignores
  # SIGINT), sends SIGTERM to every rank: rank 0 stops as a run does, the servers wait
  # for it; nothing is left running, and what was computed is on disk.
  string(JOIN " " launch ${mpirun} -n 2 ${RUMBLE} run ${scenario} --output ${WORK_DIR}/stopped
         --set /time/end=0.5 --set /time/macro_step=1e-5)
  # Lines, not ';': the script passes through a CMake list.
  rumble_run(out code sh -c "${launch} & pid=$!\nsleep 3\nkill -TERM $pid\nwait $pid")
  file(READ ${WORK_DIR}/stopped/summary.json summary)
  string(JSON status GET "${summary}" status)
  if(NOT status STREQUAL "interrupted")
    message(FATAL_ERROR "summary.json status '${status}', expected 'interrupted':\n${out}")
  endif()
  expect_match("${out}" "interrupted at t = [0-9.e-]+ s")
elseif(CASE STREQUAL "foreign_launcher_is_refused")
  # Another MPI's launcher (MPICH's hydra sets PMI_SIZE and PMI_RANK): OpenMPI would run each
  # process as a world of one, N copies of the whole run; the engine stops and says why.
  set(ENV{PMI_SIZE} 2)
  set(ENV{PMI_RANK} 0)
  rumble_run(out code ${RUMBLE} plugins)
  if(NOT code EQUAL 3)
    message(FATAL_ERROR "expected exit code 3, got ${code}:\n${out}")
  endif()
  expect_match("${out}" "the launcher started 2 processes but MPI sees each alone .*use that MPI's mpirun")
elseif(CASE STREQUAL "study_spreads_runs_over_ranks")
  # Three runs on two ranks: the first and third on rank 0, the second on rank 1 (k mod N), each
  # a process of its own (its environment without the launcher's), rank 0 writing study.json.
  file(COPY ${scenario} DESTINATION ${WORK_DIR})
  file(WRITE ${WORK_DIR}/spread.study.json [=[
{"study_version": 1, "scenario": "split_dashpot.json", "jobs": 1,
 "axes": [{"name": "k", "values": {"soft": {"/soil/params/stiffness": 5e7},
                                    "mid": {"/soil/params/stiffness": 1e8},
                                    "hard": {"/soil/params/stiffness": 2e8}}}]}
]=])
  rumble_run(out code ${mpirun} -n 2 ${RUMBLE} study ${WORK_DIR}/spread.study.json --no-report)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "the study on 2 ranks failed (${code}):\n${out}")
  endif()
  file(READ ${WORK_DIR}/results/spread.study/study.json state)
  foreach(k RANGE 2)
    string(JSON name GET "${state}" runs ${k} name)
    string(JSON status GET "${state}" runs ${k} status)
    string(JSON rank GET "${state}" runs ${k} mpi rank)
    math(EXPR expected "${k} % 2")
    if(NOT status STREQUAL "completed" OR NOT rank EQUAL expected)
      message(FATAL_ERROR "run ${name}: ${status} on rank ${rank} (expected completed on rank "
                          "${expected}):\n${state}")
    endif()
    file(READ ${WORK_DIR}/results/spread.study/${name}/run.log log)
    expect_match("${log}" "rank 0 of 1 ranks owns 40 footprints")  # its own process, one rank
  endforeach()
elseif(CASE STREQUAL "idle_ranks_are_named")
  rumble_run(out code ${mpirun} -n 3 ${RUMBLE} run ${scenario} --output ${WORK_DIR}/idle
             --set [=[/soil={"type": "winkler", "params": {"k": 1e8, "c": 1e5}}]=]
             --set /time/end=0.005 --no-plots)
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "the winkler run on 3 ranks failed (${code}):\n${out}")
  endif()
  expect_match("${out}" "launched on 3 MPI ranks, but soil type 'winkler' runs on one .*the other 2 ranks wait idle")
  string(REGEX MATCHALL "wait idle" said "${out}")
  list(LENGTH said n)
  if(NOT n EQUAL 1)
    message(FATAL_ERROR "said ${n} times, expected once:\n${out}")
  endif()
else()
  message(FATAL_ERROR "unknown case ${CASE}")
endif()
