#pragma once
// <coif/coif.h>: the runtime of coif (CMake target coif::runtime), everything a program needs to load a cooked
// hair asset and draw it, and nothing that cooks one (no HRIR database, FLANN, Ceres, Embree or GLFW).
//
//   find_package(coif CONFIG REQUIRED COMPONENTS runtime)
//   target_link_libraries(game PRIVATE coif::runtime)
//
// Cook once, with the command: `coif bake style.json -o hair.coif` (online/shells/hair_asset.h documents the file
// and its compatibility rule). Then draw it into your frame with coif::HairRenderer (online/hair_renderer.h: the
// camera, depth convention, GL state, errors, threading and lifetimes). For offscreen work without a window,
// coif::gl::Context::headless() (online/gl_context.h) makes an EGL context. A character: models/character.h reads its
// body (read_body), models/skinning.h poses it (BonePose, skin_body) as the hair's bones follow it, and
// models/animation.h reads `coif render --animate`'s keyframes.
//
// No header here includes a GL header or loader: use your own.
#include "models/core/camera.h"
#include "models/core/error.h"
#include "models/core/log.h"
#include "models/animation.h"
#include "models/character.h"
#include "models/skinning.h"
#include "online/gl_context.h"
#include "online/hair_renderer.h"
#include "online/shells/hair_asset.h"
#include "online/shells/shell_settings.h"
#include "shaders/srbf_light.h"
