# `shapestruct-mpi analyze` across MPI ranks (issue 15): 10 generated chairs and a bad shape, analysed by one
# process (`shapestruct`) and by R ranks of `mpirun -np R shapestruct-mpi` into separate folders; every result
# file must be the same byte for byte. Left out of the comparison: timings.json/js (seconds) and the resume cache
# fuzzy/pairs/*.align, which records each alignment's wall time (the same pairs must be there). Run by CTest as
#   cmake -DCLI=<shapestruct> -DMPI_CLI=<shapestruct-mpi> -DMPIEXEC=<mpirun> -DRANKS="2" -DWORK=<scratch>
#         -P analyze_mpi.cmake
file(REMOVE_RECURSE ${WORK})
file(MAKE_DIRECTORY ${WORK})
include(${CMAKE_CURRENT_LIST_DIR}/run_cli.cmake)

set(IN ${WORK}/chairs)
run_cli(0 out generate chairs 10 -o ${IN} --seed 3)
file(WRITE ${IN}/empty.off "OFF\n0 0 0\n")
run_cli(0 alone analyze ${IN} -o ${WORK}/one --threads 1 --quiet)

# OpenMPI as root in a container: allow root, more ranks than cores, no cross-memory attach.
set(ENV{OMPI_MCA_btl_vader_single_copy_mechanism} none)
set(mpirun ${MPIEXEC} --allow-run-as-root --oversubscribe)

hash_tree(${WORK}/one reference "^$" "^fuzzy/pairs/")

foreach(R IN LISTS RANKS)
  string(TIMESTAMP t0 "%s")
  execute_process(COMMAND ${mpirun} -np ${R} ${MPI_CLI} analyze ${IN} -o ${WORK}/ranks${R} --threads 1
                  RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 600)
  string(TIMESTAMP t1 "%s")
  if(NOT code EQUAL 0)
    message(FATAL_ERROR "mpirun -np ${R} shapestruct-mpi analyze: exit code ${code}\n${out}\n${err}")
  endif()
  string(REGEX MATCHALL "accuracy: " said "${out}")
  list(LENGTH said n)
  if(NOT n EQUAL 1)
    message(FATAL_ERROR "${R} ranks: the summary should be printed once (by rank 0), seen ${n} times:\n${out}")
  endif()
  hash_tree(${WORK}/ranks${R} shared "^$" "^fuzzy/pairs/")
  if(NOT shared STREQUAL reference)
    message(FATAL_ERROR "${R} ranks wrote other files than one process:\n--- one process\n${reference}\n--- ${R} ranks\n${shared}")
  endif()
  math(EXPR seconds "${t1} - ${t0}")
  message(STATUS "${R} ranks: the same files as one process, byte for byte (${seconds} s)")
endforeach()

# A command that does not run across ranks is refused, by name, instead of running R times.
execute_process(COMMAND ${mpirun} -np 2 ${MPI_CLI} inspect ${IN}/chair_000000.off
                RESULT_VARIABLE code OUTPUT_VARIABLE out ERROR_VARIABLE err TIMEOUT 120)
if(code EQUAL 0 OR NOT "${out}${err}" MATCHES "only 'analyze' runs across")
  message(FATAL_ERROR "shapestruct-mpi inspect on 2 ranks: exit code ${code}, expected a refusal:\n${out}\n${err}")
endif()
