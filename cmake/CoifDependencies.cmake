# Every dependency comes from a Debian 12 package (cmake/apt-packages.txt); nothing is vendored. They come in
# tiers, so that a build of the runtime alone (COIF_BUILD_AUTHORING=OFF) needs only the first:
#   runtime    what coif::runtime links (load a cooked .coif asset and draw it): glm, nlohmann_json, OpenImageIO,
#              xxHash, libepoxy, EGL, threads, tinyobjloader (a character's body from .obj).
#              cmake/coifConfig.cmake.in finds the same for a consumer.
#   authoring  the offline tools and the database (coif::offline, coif::db, coif::scene): Ceres, Embree, FLANN.
#   tools      the coif command and its viewer: CLI11, GLFW.
#   tests      GoogleTest.
find_package(glm CONFIG REQUIRED)
find_package(nlohmann_json CONFIG REQUIRED)
find_package(PkgConfig REQUIRED)
# OpenImageIO through pkg-config: Debian 12's CMake config of OpenImageIO names /usr/include/opencv4
# (present only with libopencv-dev) in its include paths, which breaks configuration without OpenCV.
pkg_check_modules(OIIO REQUIRED IMPORTED_TARGET OpenImageIO)
pkg_check_modules(XXHASH REQUIRED IMPORTED_TARGET libxxhash)
pkg_check_modules(EPOXY REQUIRED IMPORTED_TARGET epoxy)
pkg_check_modules(EGL REQUIRED IMPORTED_TARGET egl)
find_package(Threads REQUIRED)
find_package(tinyobjloader CONFIG REQUIRED)  # libtinyobjloader-dev: Wavefront .obj bodies (models/character.h)
if(COIF_BUILD_AUTHORING)
  find_package(Ceres CONFIG REQUIRED)
  find_package(embree 3 CONFIG REQUIRED)   # Embree 3 (libembree-dev): curve ray tracing of the reference renderer
  pkg_check_modules(FLANN REQUIRED IMPORTED_TARGET flann)
endif()
if(COIF_BUILD_TOOLS)
  find_package(CLI11 CONFIG REQUIRED)
  find_package(glfw3 CONFIG REQUIRED)
  # Dear ImGui (libimgui-dev 1.86): the core as a library; its GLFW and OpenGL 3 backends ship only as example
  # sources in the package's documentation, compiled by online/window/ (setup.sh extracts them from the package when
  # a system drops /usr/share/doc).
  pkg_check_modules(IMGUI REQUIRED IMPORTED_TARGET imgui)
  find_path(COIF_IMGUI_BACKENDS imgui_impl_glfw.cpp
            PATHS /usr/share/doc/libimgui-dev/examples/backends
                  ${PROJECT_SOURCE_DIR}/build/deb/root/usr/share/doc/libimgui-dev/examples/backends
            NO_DEFAULT_PATH)
  if(NOT COIF_IMGUI_BACKENDS)
    message(FATAL_ERROR "Dear ImGui's GLFW/OpenGL3 backend sources are missing (libimgui-dev's examples/backends); "
                        "run ./setup.sh build, which installs or extracts them")
  endif()
endif()
if(COIF_BUILD_TESTS)
  find_package(GTest CONFIG REQUIRED)
endif()
