# Validation and repair (CGAL). The heavy templates live in the few src/repair/Cgal*.cpp units.
find_package(CGAL REQUIRED)
find_package(TBB REQUIRED)
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
reamsim_add_module(mesh_repair
  SOURCES
    src/repair/EdgeTopology.cpp
    src/repair/Validation.cpp
    src/repair/Repair.cpp
    src/repair/VolumetricRemesh.cpp
    src/repair/FastWindingNumber.cpp
    src/repair/MarchingTetrahedra.cpp
    src/repair/CgalSelfIntersections.cpp
    src/repair/CgalSoupRepair.cpp
    src/repair/CgalDistanceOracle.cpp
    src/repair/CgalDecimate.cpp
  PUBLIC_DEPS reamsim::mesh
  PRIVATE_DEPS CGAL::CGAL Eigen3::Eigen TBB::tbb nlohmann_json::nlohmann_json)
