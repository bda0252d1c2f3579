#pragma once
// A scene (scenes/scene.hpp) from a Python argument, shared by lcprelax.Simulator and
// lcprelax.SceneObjective: a str whose first non-blank character is '{' is parsed as scene
// JSON text (parse_scene); any other str or os.PathLike is a file path (load_scene, whose
// errors start with "PATH: "). Another type is a TypeError; a malformed scene an InputError
// naming the field (scenes/scene_json.hpp). Parsing releases the GIL. Defined in simulator.cpp.
#include "bindings.hpp"

#include <lcprelax/scenes/scene.hpp>

namespace lcprelax::python {

Scene scene_from_python(const py::object& source);

}  // namespace lcprelax::python
