# Mesh type and file I/O. (Owned by the mesh I/O work; extend the source list here.)
find_package(VTK REQUIRED COMPONENTS IOXML CommonCore CommonDataModel FiltersCore)
find_package(ZLIB REQUIRED)  # the VTP reader's compressed blocks

reamsim_add_module(mesh
  SOURCES
    src/TriangleMesh.cpp
    src/ClosestPoints.cpp
    src/io/FileBytes.cpp
    src/io/FileReplace.cpp
    src/io/TextScanner.cpp
    src/io/MeshBuilder.cpp
    src/io/StlIO.cpp
    src/io/ObjIO.cpp
    src/io/PlyIO.cpp
    src/io/OffIO.cpp
    src/io/VtpIO.cpp
    src/io/VtpReader.cpp
    src/io/VtpScanner.cpp
    src/io/MeshIO.cpp
  PRIVATE_DEPS
    VTK::IOXML VTK::CommonCore VTK::CommonDataModel VTK::FiltersCore ZLIB::ZLIB
)
vtk_module_autoinit(TARGETS reamsim_mesh MODULES VTK::IOXML VTK::CommonCore VTK::CommonDataModel VTK::FiltersCore)
