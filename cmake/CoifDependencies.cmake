# Every dependency comes from a Debian 12 package (cmake/apt-packages.txt); nothing is vendored.
find_package(glm CONFIG REQUIRED)
find_package(OpenEXR CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
find_package(CLI11 CONFIG REQUIRED)
find_package(glfw3 CONFIG REQUIRED)
find_package(GTest CONFIG REQUIRED)
find_package(benchmark CONFIG REQUIRED)
find_package(Ceres CONFIG REQUIRED)
find_package(embree 3 CONFIG REQUIRED)   # Embree 3 (libembree-dev): curve ray tracing of the reference renderer
find_package(PkgConfig REQUIRED)
# OpenImageIO through pkg-config: Debian 12's CMake config of OpenImageIO names /usr/include/opencv4
# (present only with libopencv-dev) in its include paths, which breaks configuration without OpenCV.
pkg_check_modules(OIIO REQUIRED IMPORTED_TARGET OpenImageIO)
pkg_check_modules(EPOXY REQUIRED IMPORTED_TARGET epoxy)
pkg_check_modules(EGL REQUIRED IMPORTED_TARGET egl)
pkg_check_modules(FLANN REQUIRED IMPORTED_TARGET flann)
pkg_check_modules(XXHASH REQUIRED IMPORTED_TARGET libxxhash)
find_package(Threads REQUIRED)
