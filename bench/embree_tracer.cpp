#include "embree_tracer.h"

#ifdef RAYLANE_HAVE_EMBREE

#include <embree3/rtcore.h>

#include <atomic>
#include <chrono>
#include <map>
#include <memory>
#include <mutex>

namespace raylane::bench {

struct EmbreeScene::Impl {
  RTCDevice device = nullptr;
  RTCScene scene = nullptr;
  const Scene* source = nullptr;
};

namespace {

std::atomic<std::ptrdiff_t> g_embree_bytes{0};

bool count_memory(void*, ssize_t bytes, bool) {
  g_embree_bytes += bytes;
  return true;
}

RTCDevice device() {
  static RTCDevice d = [] {
    RTCDevice dev = rtcNewDevice(nullptr);
    rtcSetDeviceMemoryMonitorFunction(dev, count_memory, nullptr);
    return dev;
  }();
  return d;
}

void add_triangles(RTCScene s, const TriangleTable& t) {
  if (t.size() == 0) return;
  RTCGeometry g = rtcNewGeometry(device(), RTC_GEOMETRY_TYPE_TRIANGLE);
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT3, 12, t.size() * 3));
  auto* idx = static_cast<uint32_t*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT3, 12, t.size()));
  for (uint32_t i = 0; i < t.size(); ++i) {
    glm::vec3 p[3] = {t.p0(i), t.p1(i), t.p2(i)};
    for (int k = 0; k < 3; ++k) {
      v[(3 * i + k) * 3 + 0] = p[k].x, v[(3 * i + k) * 3 + 1] = p[k].y;
      v[(3 * i + k) * 3 + 2] = p[k].z;
      idx[3 * i + k] = 3 * i + k;
    }
  }
  rtcCommitGeometry(g);
  rtcAttachGeometryByID(s, g, unsigned(tag_of<Triangle>));
  rtcReleaseGeometry(g);
}

void add_spheres(RTCScene s, const SphereTable& t) {
  if (t.size() == 0) return;
  RTCGeometry g = rtcNewGeometry(device(), RTC_GEOMETRY_TYPE_SPHERE_POINT);
  auto* v = static_cast<float*>(
      rtcSetNewGeometryBuffer(g, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 16, t.size()));
  for (uint32_t i = 0; i < t.size(); ++i)
    v[4 * i] = t.cx[i], v[4 * i + 1] = t.cy[i], v[4 * i + 2] = t.cz[i], v[4 * i + 3] = t.r[i];
  rtcCommitGeometry(g);
  rtcAttachGeometryByID(s, g, unsigned(tag_of<Sphere>));
  rtcReleaseGeometry(g);
}

// User geometry: bounds from the table, intersection by the double reference kernel.
template <class Kind>
struct UserGeometry {
  static const typename Kind::Table& table(void* user) {
    return static_cast<const Scene*>(user)->table<Kind>();
  }
  static void bounds(const RTCBoundsFunctionArguments* a) {
    Bounds3f b = table(a->geometryUserPtr).bounds(a->primID);
    *a->bounds_o = {b.lo.x, b.lo.y, b.lo.z, 0, b.hi.x, b.hi.y, b.hi.z, 0};
  }
  static Rayd ray_of(RTCRayN* r, unsigned n, unsigned i) {
    return {{RTCRayN_org_x(r, n, i), RTCRayN_org_y(r, n, i), RTCRayN_org_z(r, n, i)},
            {RTCRayN_dir_x(r, n, i), RTCRayN_dir_y(r, n, i), RTCRayN_dir_z(r, n, i)},
            RTCRayN_tnear(r, n, i),
            RTCRayN_tfar(r, n, i)};
  }
  static void intersect(const RTCIntersectFunctionNArguments* a) {
    RTCRayN* ray = RTCRayHitN_RayN(a->rayhit, a->N);
    RTCHitN* hit = RTCRayHitN_HitN(a->rayhit, a->N);
    for (unsigned i = 0; i < a->N; ++i) {
      if (a->valid[i] != -1) continue;
      double t = intersect_ref(table(a->geometryUserPtr), a->primID, ray_of(ray, a->N, i));
      if (!(t < RTCRayN_tfar(ray, a->N, i))) continue;
      RTCRayN_tfar(ray, a->N, i) = float(t);
      RTCHitN_primID(hit, a->N, i) = a->primID;
      RTCHitN_geomID(hit, a->N, i) = a->geomID;
      RTCHitN_instID(hit, a->N, i, 0) = RTC_INVALID_GEOMETRY_ID;
    }
  }
  static void occluded(const RTCOccludedFunctionNArguments* a) {
    for (unsigned i = 0; i < a->N; ++i) {
      if (a->valid[i] != -1) continue;
      double t = intersect_ref(table(a->geometryUserPtr), a->primID, ray_of(a->ray, a->N, i));
      if (t < RTCRayN_tfar(a->ray, a->N, i)) RTCRayN_tfar(a->ray, a->N, i) = -INFINITY;
    }
  }
  static void add(RTCScene s, const Scene& scene) {
    if (scene.table<Kind>().size() == 0) return;
    RTCGeometry g = rtcNewGeometry(device(), RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(g, unsigned(scene.table<Kind>().size()));
    rtcSetGeometryUserData(g, const_cast<Scene*>(&scene));
    rtcSetGeometryBoundsFunction(g, bounds, nullptr);
    rtcSetGeometryIntersectFunction(g, intersect);
    rtcSetGeometryOccludedFunction(g, occluded);
    rtcCommitGeometry(g);
    rtcAttachGeometryByID(s, g, unsigned(tag_of<Kind>));
    rtcReleaseGeometry(g);
  }
};

RTCScene build(const Scene& scene, EmbreeMode mode, double* seconds) {
  RTCScene s = rtcNewScene(device());
  // ROBUST avoids optimisations that reduce arithmetic accuracy, and its triangle test is
  // watertight (Embree 3 API manual, rtcSetSceneFlags).
  if (mode == EmbreeMode::kRobust) rtcSetSceneFlags(s, RTC_SCENE_FLAG_ROBUST);
  add_spheres(s, scene.table<Sphere>());
  UserGeometry<Box>::add(s, scene);
  UserGeometry<Cylinder>::add(s, scene);
  UserGeometry<Csg>::add(s, scene);  // Embree has no CSG: raylane's reference in user geometry
  UserGeometry<Sdf>::add(s, scene);  // nor ray marching: raylane's double reference marcher
  add_triangles(s, scene.table<Triangle>());
  auto start = std::chrono::steady_clock::now();
  rtcCommitScene(s);
  *seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  return s;
}

RTCRay embree_ray(const RayStream& rays, std::size_t i) {
  RTCRay r{};
  r.org_x = rays.ox[i], r.org_y = rays.oy[i], r.org_z = rays.oz[i];
  r.dir_x = rays.dx[i], r.dir_y = rays.dy[i], r.dir_z = rays.dz[i];
  r.tnear = rays.tmin[i], r.tfar = rays.tmax[i];
  r.mask = ~0u;
  return r;
}

uint32_t prim_of(unsigned geom, unsigned prim) {
  return geom == RTC_INVALID_GEOMETRY_ID ? PrimRef::kInvalidBits
                                         : PrimRef(PrimTag(geom), prim).bits();
}

void trace_one(RTCScene s, const RayStream& rays, std::size_t i, bool occlusion, HitStream& h) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  RTCRay r = embree_ray(rays, i);
  if (occlusion) {
    rtcOccluded1(s, &ctx, &r);
    h.t[i] = 0, h.prim[i] = r.tfar < 0 ? 0u : PrimRef::kInvalidBits;
    return;
  }
  RTCRayHit rh{r, {}};
  rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
  rtcIntersect1(s, &ctx, &rh);
  h.prim[i] = prim_of(rh.hit.geomID, rh.hit.primID);
  h.t[i] = h.prim[i] == PrimRef::kInvalidBits ? INFINITY : rh.ray.tfar;
}

void trace_sixteen(RTCScene s, const RayStream& rays, std::size_t i0, bool occlusion,
                   HitStream& h) {
  RTCIntersectContext ctx;
  rtcInitIntersectContext(&ctx);
  alignas(64) int valid[16];
  alignas(64) RTCRayHit16 rh;
  std::size_t n = std::min<std::size_t>(16, rays.size() - i0);
  for (std::size_t k = 0; k < 16; ++k) {
    valid[k] = k < n ? -1 : 0;
    RTCRay r = k < n ? embree_ray(rays, i0 + k) : RTCRay{};
    rh.ray.org_x[k] = r.org_x, rh.ray.org_y[k] = r.org_y, rh.ray.org_z[k] = r.org_z;
    rh.ray.dir_x[k] = r.dir_x, rh.ray.dir_y[k] = r.dir_y, rh.ray.dir_z[k] = r.dir_z;
    rh.ray.tnear[k] = r.tnear, rh.ray.tfar[k] = r.tfar;
    rh.ray.mask[k] = ~0u, rh.ray.time[k] = 0, rh.ray.flags[k] = 0, rh.ray.id[k] = unsigned(k);
    rh.hit.geomID[k] = RTC_INVALID_GEOMETRY_ID;
  }
  if (occlusion) {
    rtcOccluded16(valid, s, &ctx, &rh.ray);
  } else {
    rtcIntersect16(valid, s, &ctx, &rh);
  }
  for (std::size_t k = 0; k < n; ++k) {
    if (occlusion) {
      h.t[i0 + k] = 0, h.prim[i0 + k] = rh.ray.tfar[k] < 0 ? 0u : PrimRef::kInvalidBits;
    } else {
      h.prim[i0 + k] = prim_of(rh.hit.geomID[k], rh.hit.primID[k]);
      h.t[i0 + k] = h.prim[i0 + k] == PrimRef::kInvalidBits ? INFINITY : rh.ray.tfar[k];
    }
  }
}

}  // namespace

bool embree_available() {
  return true;
}

const EmbreeScene* embree_scene(const BenchScene& b, EmbreeMode mode) {
  static std::mutex mutex;
  static std::map<std::pair<const BenchScene*, EmbreeMode>, std::unique_ptr<EmbreeScene>> cache;
  std::lock_guard<std::mutex> lock(mutex);
  auto& slot = cache[{&b, mode}];
  if (!slot) {
    slot = std::make_unique<EmbreeScene>();
    slot->impl = new EmbreeScene::Impl{device(), nullptr, &b.scene};
    double seconds;
    slot->impl->scene = build(b.scene, mode, &seconds);
  }
  return slot.get();
}

EmbreeBuild embree_build_once(const BenchScene& b, EmbreeMode mode) {
  EmbreeBuild out;
  std::ptrdiff_t before = g_embree_bytes;
  RTCScene s = build(b.scene, mode, &out.seconds);
  out.bytes = std::size_t(g_embree_bytes - before);
  rtcReleaseScene(s);
  return out;
}

void EmbreeScene::trace(const RayStream& rays, bool occlusion, int width, HitStream& hits) const {
  hits.resize(rays.size());
  RTCScene s = impl->scene;
  const std::ptrdiff_t n = std::ptrdiff_t(rays.size());
  if (width == 1) {
#pragma omp parallel for schedule(dynamic, 256)
    for (std::ptrdiff_t i = 0; i < n; ++i)
      trace_one(s, rays, std::size_t(i), occlusion, hits);
  } else {
#pragma omp parallel for schedule(dynamic, 16)
    for (std::ptrdiff_t i = 0; i < n; i += 16)
      trace_sixteen(s, rays, std::size_t(i), occlusion, hits);
  }
}

}  // namespace raylane::bench

#else  // no Embree: the baseline is simply absent from the tracer list

namespace raylane::bench {
bool embree_available() {
  return false;
}
const EmbreeScene* embree_scene(const BenchScene&, EmbreeMode) {
  return nullptr;
}
EmbreeBuild embree_build_once(const BenchScene&, EmbreeMode) {
  return {};
}
void EmbreeScene::trace(const RayStream&, bool, int, HitStream&) const {}
}  // namespace raylane::bench

#endif
