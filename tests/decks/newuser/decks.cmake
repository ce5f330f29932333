# Scenes a new user writes from README and docs alone, for what the suite's own decks lack
# (newuser/<deck>.check beside each deck; the .msh committed beside its .geo): exit code 0, status
# completed, every check holding.  Included from tests/decks/CMakeLists.txt.
file(GLOB newuser_checks CONFIGURE_DEPENDS ${CMAKE_CURRENT_SOURCE_DIR}/newuser/*.check)
foreach(check IN LISTS newuser_checks)
  get_filename_component(name ${check} NAME_WE)
  add_test(NAME newuser_${name}
    COMMAND ${CMAKE_COMMAND} -DEXE=$<TARGET_FILE:kontakt2d> -DDECK=${CMAKE_CURRENT_SOURCE_DIR}/newuser/${name}.dat
            -DWORK=${K2D_DECK_WORK} -DARGS=-q -DH5DUMP=${H5DUMP_EXECUTABLE} ${K2D_CHECK_ARGS}
            -P ${CMAKE_CURRENT_SOURCE_DIR}/run_good_deck.cmake)
  set_tests_properties(newuser_${name} PROPERTIES LABELS regression ENVIRONMENT "${K2D_PYTHONPATH};OPENBLAS_NUM_THREADS=1")
endforeach()
