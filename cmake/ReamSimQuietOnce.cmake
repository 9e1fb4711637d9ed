# Executables and the GUI's plugins route their pthread_once calls (std::call_once: CGAL's lazy exact
# evaluation, std::promise) to a version that makes a system call only when a thread waits
# (modules/core/src/QuietPthreadOnce.cpp; a reaming cut makes ~700 first calls, each a futex wake under
# glibc: 3-13 % of a cut on the bundled scapula, docs/CSG.md). Off in sanitizer builds, whose runtimes
# intercept pthread_once themselves.
option(REAMSIM_QUIET_ONCE "Link executables with the quiet pthread_once" ON)

function(reamsim_use_quiet_once target)
  if(REAMSIM_QUIET_ONCE AND NOT REAMSIM_SANITIZE)
    target_link_libraries(${target} PRIVATE reamsim_quiet_once)
  endif()
endfunction()
