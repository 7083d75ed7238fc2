#pragma once
// The --dump-projections sidecar: for each view its rectangle in the picture and, per body, its
// state, its colour and where it appears (the projected origin and the projected box of its
// bounds), so a test can look at the pixels where each body must be.
#include <string>
#include <vector>

#include "batch.hpp"
#include "camera.hpp"
#include "renderer.hpp"
#include "views.hpp"

namespace anyphys::testbed {

/// Writes the sidecar for `views`, drawn in `rects` with `batches` (one each) by `camera`, in a
/// picture `width` x `height`. Throws anyphys::Error naming the file if it cannot write.
void writeProjections(const std::string& path, const Views& views, const std::vector<Batch>& batches,
                      const std::vector<Rect>& rects, const Camera& camera, int width, int height);

}  // namespace anyphys::testbed
