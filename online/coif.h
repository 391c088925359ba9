#pragma once
// <coif/coif.h>: the runtime of coif (CMake target coif::runtime), everything a program needs to load a cooked
// hair asset and draw it, and nothing that cooks one (no HRIR database, FLANN, Ceres, Embree or GLFW).
//
//   find_package(coif CONFIG REQUIRED COMPONENTS runtime)
//   target_link_libraries(game PRIVATE coif::runtime)
//
// Cook once, with the command: `coif bake style.json -o hair.coif` (online/shells/hair_asset.h documents the file
// and its compatibility rule). Then, with a current OpenGL 4.5 core context (yours, or coif::gl::Context::headless()
// for offscreen work):
//
//   coif::gl::ShellRenderer hair(coif::read_hair_asset("hair.coif"));   // uploads; throws coif::Error
//   hair.set_lights(lights);                                            // SRBF lights (shaders/srbf_light.h)
//   coif::Image image = hair.render(camera, settings);                  // offscreen, linear RGBA
//
// Errors: every function throws coif::Error (models/core/error.h), naming the file and the place. Threading: one GL
// context per renderer, used from the thread where that context is current. Lifetimes: a renderer owns its GL
// objects and must be destroyed while its context is current.
#include "models/core/camera.h"
#include "models/core/error.h"
#include "models/core/image.h"
#include "online/gl_context.h"
#include "online/shell_renderer.h"
#include "online/shells/hair_asset.h"
#include "online/shells/shell_settings.h"
#include "shaders/srbf_light.h"
