#pragma once
// Everything game code needs.
#include "anyphys/body.hpp"
#include "anyphys/containers/material_library.hpp"
#include "anyphys/containers/scene.hpp"
#include "anyphys/defs.hpp"
#include "anyphys/error.hpp"
#include "anyphys/joint.hpp"
#include "anyphys/joint_def.hpp"
#include "anyphys/listeners/contact_listener.hpp"
#include "anyphys/world.hpp"
#include "anyphys/scene_objects.hpp"
#include "anyphys/world_settings.hpp"
#include "anyphys/backends.hpp"
