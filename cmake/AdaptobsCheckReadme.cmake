# The README's C++ code block is examples/readme_usage.cpp, character for
# character: CTest builds and runs that file (example_readme_usage), so the block
# a reader copies is a program that compiles and passes. This check compiles
# nothing; it fails when the block and the file differ, naming the first line
# that differs.
#
# Run as a script (CTest `readme_code_block`):
#   cmake -DREADME=<README.md> -DSOURCE=<examples/readme_usage.cpp> -P AdaptobsCheckReadme.cmake
# The block is the first ```cpp block after the README's mention of SOURCE's
# file name (`examples/readme_usage.cpp`).
cmake_minimum_required(VERSION 3.20)

foreach(var README SOURCE)
  if(NOT DEFINED ${var})
    message(FATAL_ERROR "AdaptobsCheckReadme.cmake: ${var} is not set")
  endif()
endforeach()

file(READ "${README}" readme)
file(READ "${SOURCE}" source)
get_filename_component(source_name "${SOURCE}" NAME)

string(FIND "${readme}" "examples/${source_name}" mention)
if(mention EQUAL -1)
  message(FATAL_ERROR "${README} does not mention examples/${source_name}")
endif()
string(SUBSTRING "${readme}" ${mention} -1 readme)
set(fence_open "```cpp\n")
string(FIND "${readme}" "${fence_open}" open)
if(open EQUAL -1)
  message(FATAL_ERROR "${README} has no ```cpp block after its mention of examples/${source_name}")
endif()
string(LENGTH "${fence_open}" fence_length)
math(EXPR start "${open} + ${fence_length}")
string(SUBSTRING "${readme}" ${start} -1 readme)
# The block ends at the first fence at the start of a line.
string(FIND "${readme}" "\n```" close)
if(close EQUAL -1)
  message(FATAL_ERROR "${README}: the ```cpp block after examples/${source_name} is not closed")
endif()
math(EXPR block_length "${close} + 1")
string(SUBSTRING "${readme}" 0 ${block_length} block)

if(block STREQUAL source)
  message(STATUS "the README's C++ block is ${SOURCE}")
  return()
endif()

# Name the first line that differs: the two texts are walked line by line.
set(line 1)
while(TRUE)
  string(FIND "${block}" "\n" block_end)
  string(FIND "${source}" "\n" source_end)
  if(block_end EQUAL -1)
    set(block_line "${block}")
  else()
    string(SUBSTRING "${block}" 0 ${block_end} block_line)
  endif()
  if(source_end EQUAL -1)
    set(source_line "${source}")
  else()
    string(SUBSTRING "${source}" 0 ${source_end} source_line)
  endif()
  if(NOT block_line STREQUAL source_line OR block_end EQUAL -1 OR source_end EQUAL -1)
    break()
  endif()
  math(EXPR block_end "${block_end} + 1")
  math(EXPR source_end "${source_end} + 1")
  string(SUBSTRING "${block}" ${block_end} -1 block)
  string(SUBSTRING "${source}" ${source_end} -1 source)
  math(EXPR line "${line} + 1")
endwhile()
if(block_line STREQUAL source_line)
  set(block_line "${block_line}   (one of the two ends after this line)")
endif()
message(FATAL_ERROR "the README's C++ block differs from ${SOURCE} at line ${line} of the block:\n"
                    "  README: ${block_line}\n"
                    "  file:   ${source_line}\n"
                    "Copy the file into the README's block (or the block into the file).")
