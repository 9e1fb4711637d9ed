# Debian package of the install tree (cpack -G DEB in build/).
set(CPACK_PACKAGE_NAME "reamsim")
set(CPACK_PACKAGE_VENDOR "ReamSim developers")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "Glenoid reaming simulator with exact mesh Booleans")
set(CPACK_PACKAGE_CONTACT "reamsim@localhost")
set(CPACK_DEBIAN_PACKAGE_SHLIBDEPS ON)
set(CPACK_GENERATOR "DEB;TGZ")
install(DIRECTORY ${REAMSIM_RESOURCE_DIR}/ DESTINATION share/reamsim/resources)
include(CPack)
