# CMake generated Testfile for 
# Source directory: /work/wt/issue-5
# Build directory: /work/wt/issue-5/build-asan
# 
# This file includes the relevant testing commands required for 
# testing this directory and lists subdirectories to be tested as well.
subdirs("tests")
subdirs("examples")
