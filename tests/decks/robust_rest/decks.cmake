# Decks of Newton at zero load and in slow linear convergence (robust_rest/<deck>.check beside each
# deck; from the generated scenes 104, 91 and 49, docs/robustness.md): a correction stretched to the
# law's forces, and a body at rest on its last pairs at zero load.  Exit code 0, status completed,
# every check holding.  Included from tests/decks/CMakeLists.txt.  One BLAS thread, as the campaign.
file(GLOB robust_rest_checks CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/robust_rest/*.check)
foreach(check IN LISTS robust_rest_checks)
  get_filename_component(name ${check} NAME_WE)
  add_test(NAME robust_rest_${name}
    COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:kontakt2d> -DDECK=${CMAKE_CURRENT_SOURCE_DIR}/robust_rest/${name}.dat
            -DWORK=${K2D_DECK_WORK} -DARGS=-q -DH5DUMP=${H5DUMP_EXECUTABLE} ${K2D_CHECK_ARGS}
            -P ${CMAKE_CURRENT_SOURCE_DIR}/run_good_deck.cmake)
  set_tests_properties(robust_rest_${name} PROPERTIES LABELS regression ENVIRONMENT "${K2D_PYTHONPATH};OPENBLAS_NUM_THREADS=1")
endforeach()
