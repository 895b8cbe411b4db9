#pragma once
// A scene's setting without its objects: for scenes derived from another one (a tessellated copy,
// a subset of its objects) that must keep its camera, lights and materials.

#include "scene/scene.h"

namespace rtlab {

/// A scene with s's camera, background, lights and materials (indices unchanged) and no objects.
inline Scene setting_of(const Scene& s) {
    Scene out;
    out.camera = s.camera;
    out.background = s.background;
    out.lights = s.lights;
    out.materials = s.materials;
    return out;
}

}  // namespace rtlab
