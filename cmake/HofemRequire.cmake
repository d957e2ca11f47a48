# hofem_require(<found-variable> <what> <debian-package>): stops configuration
# with the Debian package that provides a missing dependency.
function(hofem_require found what package)
  if(NOT ${found})
    message(FATAL_ERROR
      "hofem: ${what} not found. Install the Debian package '${package}' "
      "(scripts/install-deps installs everything hofem needs).")
  endif()
endfunction()
