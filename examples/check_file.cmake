# cmake -DFILE=PATH -DEXPECT=TEXT -P check_file.cmake: fails unless the file
# PATH exists and holds a line that begins with "TEXT = ".
if(NOT EXISTS "${FILE}")
  message(FATAL_ERROR "${FILE} was not written")
endif()
file(STRINGS "${FILE}" lines REGEX "^${EXPECT} = ")
if(NOT lines)
  message(FATAL_ERROR "${FILE} has no line '${EXPECT} = ...'")
endif()
message(STATUS "${FILE}: ${lines}")
