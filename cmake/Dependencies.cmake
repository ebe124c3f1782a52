# Every dependency is a Debian package installed by scripts/setup.sh; nothing is downloaded here.
find_package(Eigen3 3.3 REQUIRED NO_MODULE)
find_package(Ceres 2.0 REQUIRED)
find_package(NLopt REQUIRED)
find_package(GSL REQUIRED)
find_package(nlohmann_json 3 REQUIRED)
find_package(CLI11 REQUIRED)
find_package(fmt REQUIRED)
find_package(spdlog REQUIRED)
find_package(OpenMP REQUIRED)
find_package(Catch2 2 REQUIRED)
find_package(SUNDIALS 6 REQUIRED)  # CVODES for the reduced-order vehicles

# Serial HDF5 with the high-level library (dimension scales, H5DS).
set(HDF5_PREFER_PARALLEL FALSE)
find_package(HDF5 REQUIRED COMPONENTS C HL)
add_library(terracal::hdf5 INTERFACE IMPORTED)
target_include_directories(terracal::hdf5 INTERFACE ${HDF5_INCLUDE_DIRS})
target_link_libraries(terracal::hdf5 INTERFACE ${HDF5_HL_LIBRARIES} ${HDF5_C_LIBRARIES})
target_compile_definitions(terracal::hdf5 INTERFACE ${HDF5_DEFINITIONS})
