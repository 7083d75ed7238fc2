#include "projections.hpp"

#include <algorithm>
#include <fstream>
#include <limits>

#include <nlohmann/json.hpp>

namespace anyphys::testbed {
namespace {

nlohmann::json vec(const Vec3& v) { return {v.x(), v.y(), v.z()}; }

}  // namespace

void writeProjections(const std::string& path, const Views& views, const std::vector<Batch>& batches,
                      const std::vector<Rect>& rects, const Camera& camera, int width, int height) {
    nlohmann::json out;
    out["width"] = width;
    out["height"] = height;
    out["background"] = {kBackground[0], kBackground[1], kBackground[2]};
    out["shading"] = {{"ambient", kAmbient}, {"diffuse", kDiffuse}};
    out["camera"] = {{"target", vec(camera.target)}, {"yaw", camera.yaw}, {"pitch", camera.pitch}, {"distance", camera.distance}};
    nlohmann::json list = nlohmann::json::array();
    for (std::size_t i = 0; i < views.views().size() && i < rects.size() && i < batches.size(); ++i) {
        const View& v = views.views()[i];
        const Rect& r = rects[i];
        nlohmann::json view;
        view["backend"] = v.backend;
        view["scene"] = v.sceneName;
        view["rect"] = {r.x, r.y, r.w, r.h};
        view["error"] = v.error;
        view["time"] = v.time();
        nlohmann::json bodies = nlohmann::json::array();
        for (std::size_t k = 0; k < v.bodies.size(); ++k) {
            const Body& b = v.bodies[k];
            nlohmann::json body;
            body["index"] = k;
            body["name"] = b.name();
            body["type"] = std::string(toString(b.type()));
            const BodyState s = b.state();
            body["position"] = vec(s.position);
            body["orientation"] = {s.orientation.w(), s.orientation.x(), s.orientation.y(), s.orientation.z()};
            body["awake"] = b.isAwake();
            auto info = batches[i].bodies.find(b.id().index);
            if (info != batches[i].bodies.end()) {
                body["color"] = {info->second.color.r, info->second.color.g, info->second.color.b};
                if (info->second.hasBounds) {
                    // The box of the projected corners of the body's bounds, in picture pixels.
                    double x0 = std::numeric_limits<double>::infinity(), y0 = x0, x1 = -x0, y1 = -x0;
                    bool allInFront = true;
                    for (int c = 0; c < 8; ++c) {
                        const Vec3 corner((c & 1) ? info->second.hi.x() : info->second.lo.x(),
                                          (c & 2) ? info->second.hi.y() : info->second.lo.y(),
                                          (c & 4) ? info->second.hi.z() : info->second.lo.z());
                        const auto p = camera.project(corner, r.w, r.h);
                        if (!p) {
                            allInFront = false;
                            break;
                        }
                        x0 = std::min(x0, p->x + r.x);
                        x1 = std::max(x1, p->x + r.x);
                        y0 = std::min(y0, p->y + r.y);
                        y1 = std::max(y1, p->y + r.y);
                    }
                    if (allInFront) body["boundsScreen"] = {x0, y0, x1, y1};
                }
            }
            if (const auto p = camera.project(s.position, r.w, r.h)) {
                body["screen"] = {p->x + r.x, p->y + r.y};
                body["depth"] = p->depth;
                body["onScreen"] = p->x >= 0 && p->x < r.w && p->y >= 0 && p->y < r.h && p->depth > -1 && p->depth < 1;
            } else {
                body["onScreen"] = false;
            }
            bodies.push_back(body);
        }
        view["bodies"] = bodies;
        list.push_back(view);
    }
    out["views"] = list;
    std::ofstream file(path);
    file << out.dump(1) << '\n';
    if (!file) throw Error("--dump-projections: cannot write " + path);
}

}  // namespace anyphys::testbed
