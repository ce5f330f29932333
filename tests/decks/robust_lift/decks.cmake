# A load that pulls the bodies apart (issue 22; docs/robustness.md, "A load that pulls the bodies
# apart"): joint_pull_off.dat takes the preload of a joint to the total factor -0.9 (a tension) and
# must fail with exit 3 and a message that says why (run_fail_deck.cmake: .exit, .expect, .status,
# .completed); the same deck taken to 0.1 and to 0 must complete on the law (.check,
# run_good_deck.cmake).  Included from tests/decks/CMakeLists.txt.  One BLAS thread, as the campaign.
foreach(name joint_unload_tenth joint_unload_zero)
  add_test(NAME robust_lift_${name}
    COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:kontakt2d> -DDECK=${CMAKE_CURRENT_SOURCE_DIR}/robust_lift/${name}.dat
            -DWORK=${K2D_DECK_WORK} -DARGS=-q -DH5DUMP=${H5DUMP_EXECUTABLE} ${K2D_CHECK_ARGS}
            -P ${CMAKE_CURRENT_SOURCE_DIR}/run_good_deck.cmake)
  set_tests_properties(robust_lift_${name} PROPERTIES LABELS regression ENVIRONMENT "${K2D_PYTHONPATH};OPENBLAS_NUM_THREADS=1")
endforeach()
set(d ${CMAKE_CURRENT_SOURCE_DIR}/robust_lift/joint_pull_off)
add_test(NAME robust_lift_joint_pull_off
  COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:kontakt2d> -DDECK=${d}.dat -DEXPECT_FILE=${d}.expect
          -DCOMPLETED_FILE=${d}.completed -DEXIT_FILE=${d}.exit -DSTATUS_FILE=${d}.status
          -DWORK=${K2D_DECK_WORK} -DH5DUMP=${H5DUMP_EXECUTABLE}
          -P ${CMAKE_CURRENT_SOURCE_DIR}/run_fail_deck.cmake)
set_tests_properties(robust_lift_joint_pull_off PROPERTIES LABELS regression ENVIRONMENT "OPENBLAS_NUM_THREADS=1")
