# Runs make_letters into OUT and compares each file with the committed one in SCENES.
file(REMOVE_RECURSE ${OUT})
file(MAKE_DIRECTORY ${OUT})
execute_process(COMMAND ${GENERATOR} ${OUT} RESULT_VARIABLE rc)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "make_letters failed: ${rc}")
endif()
foreach(name letterX.ply letterY.ply)
  execute_process(COMMAND ${CMAKE_COMMAND} -E compare_files ${OUT}/${name} ${SCENES}/${name}
                  RESULT_VARIABLE diff)
  if(NOT diff EQUAL 0)
    message(FATAL_ERROR "scenes/${name} differs from what tools/make_letters writes")
  endif()
endforeach()
