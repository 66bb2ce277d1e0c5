#include "embree_accel.h"

#include "accel.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <string>

namespace accel {

namespace embree_detail {

/// Bytes Embree holds, from its memory monitor callback, and the first error it reported.
struct MemoryMonitor {
  std::int64_t bytes = 0;       ///< Currently allocated.
  std::int64_t peak = 0;        ///< Most ever allocated.
  std::int64_t budget = 0;      ///< Allocation refused beyond this.
  bool over_budget = false;     ///< An allocation was refused.
  std::string error;            ///< Embree's first error message, if any.
};

namespace {

bool on_memory(void* user, ssize_t bytes, bool post) {
  // Embree calls once per (de)allocation, before it (post = false; refusable) or after it.
  auto* m = static_cast<MemoryMonitor*>(user);
  if (!post && bytes > 0 && m->bytes + bytes > m->budget) {
    m->over_budget = true;
    return false;  // Embree fails the build with RTC_ERROR_OUT_OF_MEMORY
  }
  m->bytes += bytes;
  m->peak = std::max(m->peak, m->bytes);
  return true;
}

void on_error(void* user, RTCError, const char* message) {
  auto* m = static_cast<MemoryMonitor*>(user);
  if (m->error.empty()) m->error = message ? message : "unknown error";
}

struct BoxesView {
  const Aabb* boxes;
};

void bounds_fn(const RTCBoundsFunctionArguments* args) {
  const Aabb& b = static_cast<const BoxesView*>(args->geometryUserPtr)->boxes[args->primID];
  // Padded outward by a few ulps, as Bvh pads its nodes: a hit computed on the box face must
  // not be culled by rounding.
  const float px = box_pad(b.lo.x, b.hi.x), py = box_pad(b.lo.y, b.hi.y), pz = box_pad(b.lo.z, b.hi.z);
  RTCBounds* o = args->bounds_o;
  o->lower_x = b.lo.x - px;
  o->lower_y = b.lo.y - py;
  o->lower_z = b.lo.z - pz;
  o->upper_x = b.hi.x + px;
  o->upper_y = b.hi.y + py;
  o->upper_z = b.hi.z + pz;
}

const QueryContext& query_of(RTCIntersectContext* c) { return *reinterpret_cast<const QueryContext*>(c); }

// The callbacks serve rtcIntersect1/4/8/16 and rtcOccluded1/4/8/16. Embree hands them N lanes
// of its own: the caller's whole packet, part of it, reordered copies, or single rays, depending
// on its instruction set. The ray's id (set to the caller's lane by fill_lane) says which of the
// caller's rays a lane is. Embree's emulation of a packet wider than its instruction set (an
// rtcIntersect8 at sse2) also hands over the lanes the valid mask turned off, marked valid:
// ids past the query's rays are skipped.
void intersect_fn(const RTCIntersectFunctionNArguments* args) {
  const QueryContext& q = query_of(args->context);
  RTCRayN* ray = RTCRayHitN_RayN(args->rayhit, args->N);
  RTCHitN* hit = RTCRayHitN_HitN(args->rayhit, args->N);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    const unsigned id = RTCRayN_id(ray, args->N, i);
    if (id >= q.count || !q.test(q, id, args->primID)) continue;
    RTCRayN_tfar(ray, args->N, i) = widen_up(q.rays[id].tmax);
    RTCHitN_primID(hit, args->N, i) = args->primID;
    RTCHitN_geomID(hit, args->N, i) = args->geomID;
  }
}

void occluded_fn(const RTCOccludedFunctionNArguments* args) {
  const QueryContext& q = query_of(args->context);
  for (unsigned i = 0; i < args->N; ++i) {
    if (!args->valid[i]) continue;
    const unsigned id = RTCRayN_id(args->ray, args->N, i);
    if (id < q.count && q.test(q, id, args->primID)) RTCRayN_tfar(args->ray, args->N, i) = -kInfinity;
  }
}

}  // namespace
}  // namespace embree_detail

EmbreeAccel::EmbreeAccel(std::span<const Aabb> boxes, const EmbreeParams& params, const BuildLimits& limits,
                         const char* owner)
    : params_(params), owner_(owner), monitor_(std::make_unique<embree_detail::MemoryMonitor>()) {
  EmbreeParams::knobs().validate(params_);  // the JSON knobs' checks, for structs built in code
  const auto start = std::chrono::steady_clock::now();
  const std::uint64_t budget = memory_budget_bytes(limits);
  monitor_->budget = budget > std::uint64_t(std::numeric_limits<std::int64_t>::max())
                         ? std::numeric_limits<std::int64_t>::max()
                         : std::int64_t(budget);

  const IsaSet cpu = cpu_isas();
  check_embree_isa(params_.isa, cpu, owner_);
  isa_ = resolve_embree_isa(params_.isa, cpu);
  packet_lanes_ = resolve_embree_packet(params_.packet, isa_);
  std::string config = "isa=" + std::string(isa_name(isa_));
  if (params_.build_threads > 0) config += ",threads=" + std::to_string(params_.build_threads);
  device_ = embree_detail::Device(rtcNewDevice(config.c_str()));
  if (!device_.get()) throw knobs::ConfigError(std::string(owner_) + ": rtcNewDevice failed (config '" + config + "')");
  rtcSetDeviceErrorFunction(device_.get(), embree_detail::on_error, monitor_.get());
  rtcSetDeviceMemoryMonitorFunction(device_.get(), embree_detail::on_memory, monitor_.get());

  scene_ = new_scene();
  embree_detail::BoxesView view{boxes.data()};
  if (!boxes.empty()) {
    RTCGeometry geom = rtcNewGeometry(device_.get(), RTC_GEOMETRY_TYPE_USER);
    rtcSetGeometryUserPrimitiveCount(geom, unsigned(boxes.size()));
    rtcSetGeometryUserData(geom, &view);  // read only by bounds_fn, during the commit below
    rtcSetGeometryBoundsFunction(geom, embree_detail::bounds_fn, nullptr);
    rtcSetGeometryIntersectFunction(geom, embree_detail::intersect_fn);
    rtcSetGeometryOccludedFunction(geom, embree_detail::occluded_fn);
    rtcCommitGeometry(geom);
    rtcAttachGeometry(scene_.get(), geom);
    rtcReleaseGeometry(geom);
  }
  commit(scene_);

  stats_.primitives = boxes.size();
  stats_.prim_refs = boxes.size();
  stats_.memory_bytes = std::uint64_t(monitor_->peak);
  stats_.build_ms =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
}

embree_detail::Scene EmbreeAccel::new_scene() const {
  embree_detail::Scene scene(rtcNewScene(device_.get()));
  rtcSetSceneBuildQuality(scene.get(), params_.build_quality == EmbreeQuality::High ? RTC_BUILD_QUALITY_HIGH
                                                                                    : RTC_BUILD_QUALITY_MEDIUM);
  rtcSetSceneFlags(scene.get(), params_.robust ? RTC_SCENE_FLAG_ROBUST : RTC_SCENE_FLAG_NONE);
  return scene;
}

void EmbreeAccel::commit(const embree_detail::Scene& scene) const {
  rtcCommitScene(scene.get());
  if (monitor_->over_budget)
    throw knobs::ConfigError(std::string(owner_) + ": the build needs more than the memory budget of " +
                      std::to_string(monitor_->budget) + " bytes (raise --max-memory)");
  if (rtcGetDeviceError(device_.get()) != RTC_ERROR_NONE || !monitor_->error.empty())
    throw knobs::ConfigError(std::string(owner_) + ": build failed: " + monitor_->error);
}

std::uint64_t EmbreeAccel::allocated_bytes() const { return std::uint64_t(std::max<std::int64_t>(monitor_->bytes, 0)); }

void EmbreeAccel::replace_scene(embree_detail::Scene scene) {
  scene_ = std::move(scene);
  stats_.memory_bytes = allocated_bytes();
}

EmbreeAccel::EmbreeAccel(EmbreeAccel&&) noexcept = default;

EmbreeAccel& EmbreeAccel::operator=(EmbreeAccel&& o) noexcept {
  // Release our scene and device before the monitor their release reports to.
  scene_ = std::move(o.scene_);
  device_ = std::move(o.device_);
  monitor_ = std::move(o.monitor_);
  params_ = o.params_;
  owner_ = o.owner_;
  isa_ = o.isa_;
  packet_lanes_ = o.packet_lanes_;
  stats_ = o.stats_;
  return *this;
}

EmbreeAccel::~EmbreeAccel() = default;

}  // namespace accel
