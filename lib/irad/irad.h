#pragma once
// irad as a library: everything `irad render`, `irad compare` and `irad walkthrough` do, for
// programs of their own. Link the CMake target irad::irad (find_package(irad)).
//
//   irad::Log log;                                      // warnings (core/util/log.h: any sink)
//   irad::Scene scene = irad::load_scene("box.gltf", {}, log);   // irad/scene_setup.h
//   irad::RenderOptions options;                        // irad/render.h
//   options.size = {64, 64};
//   options.estimator = irad::Estimator::Pt;
//   const irad::RenderResult r = irad::render(scene, options, log);  // r.image, r.seconds, ...
//   irad::write_exr("box.exr", r.image);                // irad/compare.h (core/image/image_io.h)
//
// Errors are irad::Error (core/util/error.h), a std::runtime_error whose what() is one line
// "FILE: ELEMENT: MESSAGE", the CLI's message after "irad: error: ". There is no global state:
// every render() and Walkthrough owns its GL context and its ray-tracing structure.
#include "core/util/error.h"
#include "core/util/log.h"
#include "irad/compare.h"
#include "irad/parts.h"
#include "irad/render.h"
#include "irad/scene_setup.h"
#include "irad/walkthrough.h"
