# ctest: install softslc into a fresh prefix, then configure, build and run the consumer project
# (tests/package/consumer) against it with find_package(softslc). Run with -DBUILD=... -DSOURCE=...
# -DWORK=... (a scratch directory, recreated).
file(REMOVE_RECURSE "${WORK}")
execute_process(COMMAND "${CMAKE_COMMAND}" --install "${BUILD}" --prefix "${WORK}/prefix" RESULT_VARIABLE rc
                OUTPUT_QUIET)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "cmake --install failed (${rc})")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" -S "${SOURCE}/tests/package/consumer" -B "${WORK}/consumer" -G Ninja
                        "-DCMAKE_PREFIX_PATH=${WORK}/prefix" "-DSEAL_IN=${SOURCE}/examples/ladder/seal_in/seal_in.slc"
                RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "configuring the consumer project with find_package(softslc) failed (${rc})")
endif()
execute_process(COMMAND "${CMAKE_COMMAND}" --build "${WORK}/consumer" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "building the consumer project failed (${rc})")
endif()
execute_process(COMMAND "${WORK}/consumer/my_ladder_tests" RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "the consumer's tests failed (${rc})")
endif()
