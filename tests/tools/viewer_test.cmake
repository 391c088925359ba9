# Opens `coif view` in a window under Xvfb for 3 frames and checks the screenshot exists and shows hair.
file(REMOVE ${OUT})
execute_process(COMMAND ${XVFB} -a -s "-screen 0 1024x768x24" ${COIF} view --frames 3 --screenshot ${OUT}
                RESULT_VARIABLE rc OUTPUT_VARIABLE out ERROR_VARIABLE err)
if(NOT rc EQUAL 0)
  message(FATAL_ERROR "coif view failed (${rc}):\n${out}\n${err}")
endif()
if(NOT EXISTS ${OUT})
  message(FATAL_ERROR "coif view wrote no screenshot")
endif()
file(SIZE ${OUT} size)
# A 720x480 PNG of flat background compresses to ~2 KB; drawn hair makes it far larger.
if(size LESS 20000)
  message(FATAL_ERROR "the screenshot is only ${size} bytes: no hair drawn?")
endif()
message(STATUS "viewer screenshot: ${size} bytes")
