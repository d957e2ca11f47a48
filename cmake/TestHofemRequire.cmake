# Script-mode check of the missing-dependency message (run by ctest with -P).
list(APPEND CMAKE_MODULE_PATH ${CMAKE_CURRENT_LIST_DIR})
include(HofemRequire)
set(present TRUE)
hofem_require(present "something present" "never-mentioned")
set(absent FALSE)
hofem_require(absent "hypre" "libhypre-dev")
