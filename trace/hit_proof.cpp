#include "trace/hit_proof.h"

#include <cmath>

#include "core/ray_triangle.h"
#include "raster/raster.h"

namespace ssrt {

namespace {

// The pixel a continuous position falls in, or false off the frame.
bool pixelAt(float x, float y, int w, int h, int& px, int& py) {
    if (!(x >= 0.0f && y >= 0.0f && x < float(w) && y < float(h))) return false;
    px = int(x);
    py = int(y);
    return true;
}

}  // namespace

ProofInputs proofInputs(const TraceCamera& camera, ViewU32 ids, ViewF viewZ,
                        ProofTriangles triangles, ProofSettings settings) {
    requireViews("hit proof", camera.width, camera.height, {ids, viewZ});
    return {camera, ids, viewZ, triangles, settings};
}

ProvenRay proveRay(const ProofInputs& in, glm::vec3 origin, glm::vec3 direction, float fromX,
                   float fromY, bool marchHit, float hitX, float hitY) {
    ProvenRay r{RayProof::Uncertain, 0.0f};
    if (!marchHit) return r;
    const TraceCamera& cam = in.camera;
    const int w = cam.width, h = cam.height;
    int px = 0, py = 0;
    if (!pixelAt(hitX, hitY, w, h, px, py)) return r;
    const uint32_t id = in.ids.at(px, py);
    if (id == kNoPrimitive || id >= in.triangles.triangles.size()) return r;
    const ResolveTriangle& tri = in.triangles.triangles[id];
    if (tri.instance < in.triangles.cutOut.size() && in.triangles.cutOut[tri.instance]) return r;
    const glm::vec3* v = in.triangles.viewPositions.data();
    const glm::vec3 p0 = v[tri.v[0]], p1 = v[tri.v[1]], p2 = v[tri.v[2]];
    const TriangleHit th = intersectTriangle(origin, direction, p0, p1, p2, 0.0f, INFINITY);
    if (!th.hit) return r;
    const glm::vec3 q = origin + th.t * direction;
    if (!(q.z < 0.0f)) return r;
    // The side the ray meets is the side the camera sees (the camera at the view origin looks
    // along q): the two directions cross the triangle's plane the same way.
    const glm::vec3 e1 = p1 - p0, e2 = p2 - p0;
    const glm::vec3 n{e1.y * e2.z - e1.z * e2.y, e1.z * e2.x - e1.x * e2.z,
                      e1.x * e2.y - e1.y * e2.x};
    const float rayCos = (direction.x * n.x + direction.y * n.y) + direction.z * n.z;
    const float eyeCos = (q.x * n.x + q.y * n.y) + q.z * n.z;
    if (!((rayCos < 0.0f && eyeCos < 0.0f) || (rayCos > 0.0f && eyeCos > 0.0f))) return r;
    // Where the point lies on screen: that pixel shows a surface at the point's depth, so
    // nothing nearer hides it. (Not necessarily this triangle: at an edge the pixel's centre
    // may fall on its neighbour.)
    const float depth = 0.0f - q.z;
    const float qx = (q.x / depth / cam.tanHalfX + 1.0f) * (0.5f * float(w));
    const float qy = (1.0f - q.y / depth / cam.tanHalfY) * (0.5f * float(h));
    int sx = 0, sy = 0;
    if (!pixelAt(qx, qy, w, h, sx, sy)) return r;
    const float seen = in.viewZ.at(sx, sy);
    if (!(std::fabs(depth - seen) <= in.settings.thickness * seen)) return r;
    const float dx = qx - fromX, dy = qy - fromY;
    if (!(dx * dx + dy * dy >= in.settings.minPixels * in.settings.minPixels)) return r;
    return {RayProof::CertainHit, th.t};
}

}  // namespace ssrt
