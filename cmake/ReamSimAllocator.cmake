# The applications' allocator: tcmalloc (tcmalloc_minimal, Debian's libgoogle-perftools-dev). A cut allocates
# thousands of small objects (CGAL's exact lazy points, Surface_mesh elements, hash maps) and frees them again;
# under glibc's malloc that was ~10 % of a cut's time, under tcmalloc the cut on the bundled scapula runs
# 10-20 % faster (docs/CSG.md, session 19). Only the executables link it (the libraries stay neutral), and
# never a sanitizer build, whose runtime brings its own allocator.
option(REAMSIM_TCMALLOC "Link reamsim and reamsim-cli with tcmalloc_minimal" ON)
if(REAMSIM_TCMALLOC AND NOT REAMSIM_SANITIZE)
  find_package(PkgConfig REQUIRED)
  pkg_check_modules(TCMALLOC REQUIRED IMPORTED_TARGET libtcmalloc_minimal)
endif()

# Nothing calls tcmalloc by name: keep it linked even where the linker drops unreferenced libraries.
function(reamsim_use_fast_allocator target)
  if(REAMSIM_TCMALLOC AND NOT REAMSIM_SANITIZE)
    target_link_libraries(${target} PRIVATE "-Wl,--push-state,--no-as-needed" PkgConfig::TCMALLOC "-Wl,--pop-state")
  endif()
endfunction()
