#include "offline/reference.h"

#include <embree3/rtcore.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <limits>

#include "models/core/error.h"
#include "models/core/parallel.h"
#include "models/core/progress.h"
#include "models/core/random.h"
#include "models/core/units.h"
#include "shaders/envmap.h"

namespace coif {
namespace {

constexpr float kInf = std::numeric_limits<float>::infinity();

float max3(const glm::vec3& v) { return std::max(v.x, std::max(v.y, v.z)); }

// Index of the first cdf entry > x among cdf[1..n] (cdf[0] = 0, cdf[n] = 1).
int sample_cdf(const float* cdf, int n, float x) {
    const float* it = std::upper_bound(cdf + 1, cdf + n + 1, x);
    return std::clamp(static_cast<int>(it - cdf) - 1, 0, n - 1);
}

glm::vec3 uniform_sphere(float xi0, float xi1) {
    const float z = 1.0f - 2.0f * xi0, r = std::sqrt(std::max(0.0f, 1.0f - z * z)), phi = 2.0f * kPiF * xi1;
    return {r * std::cos(phi), z, r * std::sin(phi)};
}

// Orthonormal basis around a unit vector (Duff et al. 2017).
void basis(const glm::vec3& n, glm::vec3& b1, glm::vec3& b2) {
    const float sign = std::copysign(1.0f, n.z);
    const float a = -1.0f / (sign + n.z), b = n.x * n.y * a;
    b1 = {1.0f + sign * n.x * n.x * a, sign * b, -sign * n.x};
    b2 = {b, sign + n.y * n.y * a, -n.y};
}

float vmf_kappa(float lambda) { return 2.0f / (lambda * lambda); }
// Density on the sphere of exp(κ(cos γ − 1)) normalised: κ / (2π (1 − e^{−2κ})) · exp(κ(cos γ − 1)).
float vmf_pdf(float kappa, float cos_gamma) {
    return kappa / (2.0f * kPiF * static_cast<float>(-std::expm1(-2.0 * kappa))) * std::exp(kappa * (cos_gamma - 1.0f));
}

void check_finite(const glm::vec3& v, const std::string& place) {
    if (!std::isfinite(v.x) || !std::isfinite(v.y) || !std::isfinite(v.z)) throw Error::parameter(place, "must be finite");
}

}  // namespace

// ───────────────────────── environment ─────────────────────────

ReferenceEnvironment ReferenceEnvironment::constant(const glm::vec3& radiance) {
    check_finite(radiance, "constant environment");
    if (radiance.x < 0 || radiance.y < 0 || radiance.z < 0) throw Error::parameter("constant environment", "radiance must be >= 0");
    ReferenceEnvironment e;
    e.kind_ = Kind::constant;
    e.constant_ = radiance;
    char buf[96];
    std::snprintf(buf, sizeof buf, "constant environment (%g, %g, %g)", radiance.x, radiance.y, radiance.z);
    e.label_ = buf;
    return e;
}

ReferenceEnvironment ReferenceEnvironment::from_map(EnvMap map, std::string label) {
    ReferenceEnvironment e;
    e.kind_ = Kind::map;
    const int w = map.width, h = map.height;
    e.pixel_prob_.assign(static_cast<size_t>(w) * h, 0.0f);
    e.col_cdf_.assign(static_cast<size_t>(w + 1) * h, 0.0f);
    e.row_cdf_.assign(h + 1, 0.0f);
    std::vector<double> row_sum(h, 0.0);
    double total = 0;
    for (int r = 0; r < h; ++r) {
        const double omega = glsl::envmap_pixel_solid_angle(float(r), float(w), float(h));
        double acc = 0;
        for (int c = 0; c < w; ++c) {
            acc += std::max(0.0f, max3(map.at(c, r))) * omega;
            e.col_cdf_[static_cast<size_t>(r) * (w + 1) + c + 1] = static_cast<float>(acc);
        }
        row_sum[r] = acc;
        total += acc;
    }
    if (!(total > 0)) throw Error(label, "", "the environment map is black: nothing to light the hair");
    double acc = 0;
    for (int r = 0; r < h; ++r) {
        float* cdf = &e.col_cdf_[static_cast<size_t>(r) * (w + 1)];
        const double omega = glsl::envmap_pixel_solid_angle(float(r), float(w), float(h));
        for (int c = 0; c < w; ++c)
            e.pixel_prob_[static_cast<size_t>(r) * w + c] = static_cast<float>(std::max(0.0f, max3(map.at(c, r))) * omega / total);
        if (row_sum[r] > 0)
            for (int c = 1; c <= w; ++c) cdf[c] = static_cast<float>(cdf[c] / row_sum[r]);
        cdf[w] = row_sum[r] > 0 ? 1.0f : 0.0f;
        acc += row_sum[r];
        e.row_cdf_[r + 1] = static_cast<float>(acc / total);
    }
    e.row_cdf_[h] = 1.0f;
    e.map_ = std::move(map);
    e.label_ = std::move(label);
    return e;
}

ReferenceEnvironment ReferenceEnvironment::from_srbf(std::vector<SrbfLight> lights, std::string label) {
    if (lights.empty()) throw Error(label, "", "no SRBF lights");
    ReferenceEnvironment e;
    e.kind_ = Kind::srbf;
    std::vector<double> energy(lights.size());
    double total = 0;
    for (size_t j = 0; j < lights.size(); ++j) {
        lights[j].omega = glm::normalize(lights[j].omega);
        energy[j] = std::max(0.0f, max3(lights[j].L)) * glsl::srbf_integral(lights[j].lambda);
        total += energy[j];
    }
    if (!(total > 0)) throw Error(label, "", "every SRBF light is black: nothing to light the hair");
    e.light_cdf_.assign(lights.size() + 1, 0.0f);
    e.light_prob_.resize(lights.size());
    double acc = 0;
    for (size_t j = 0; j < lights.size(); ++j) {
        acc += energy[j];
        e.light_prob_[j] = static_cast<float>(energy[j] / total);
        e.light_cdf_[j + 1] = static_cast<float>(acc / total);
    }
    e.light_cdf_.back() = 1.0f;
    e.lights_ = std::move(lights);
    e.label_ = std::move(label);
    return e;
}

glm::vec3 ReferenceEnvironment::radiance(const glm::vec3& d) const {
    switch (kind_) {
        case Kind::constant: return constant_;
        case Kind::map: {
            const glm::vec2 uv = glsl::envmap_uv(d);
            const int c = std::clamp(static_cast<int>(uv.x * map_.width), 0, map_.width - 1);
            const int r = std::clamp(static_cast<int>(uv.y * map_.height), 0, map_.height - 1);
            return glm::max(map_.at(c, r), glm::vec3(0.0f));
        }
        case Kind::srbf: return evaluate_srbf_lights(lights_, d);
    }
    return glm::vec3(0.0f);
}

float ReferenceEnvironment::pdf(const glm::vec3& d) const {
    switch (kind_) {
        case Kind::constant: return 1.0f / (4.0f * kPiF);
        case Kind::map: {
            const glm::vec2 uv = glsl::envmap_uv(d);
            const int c = std::clamp(static_cast<int>(uv.x * map_.width), 0, map_.width - 1);
            const int r = std::clamp(static_cast<int>(uv.y * map_.height), 0, map_.height - 1);
            return pixel_prob_[static_cast<size_t>(r) * map_.width + c] /
                   glsl::envmap_pixel_solid_angle(float(r), float(map_.width), float(map_.height));
        }
        case Kind::srbf: {
            float p = 0;
            for (size_t j = 0; j < lights_.size(); ++j)
                p += light_prob_[j] * vmf_pdf(vmf_kappa(lights_[j].lambda), glm::dot(d, lights_[j].omega));
            return p;
        }
    }
    return 0.0f;
}

glm::vec3 ReferenceEnvironment::sample(float xi0, float xi1, float xi2, float xi3, glm::vec3& d, float& p) const {
    switch (kind_) {
        case Kind::constant:
            d = uniform_sphere(xi0, xi1);
            p = 1.0f / (4.0f * kPiF);
            return constant_;
        case Kind::map: {
            const int w = map_.width, h = map_.height;
            const int r = sample_cdf(row_cdf_.data(), h, xi0);
            const int c = sample_cdf(&col_cdf_[static_cast<size_t>(r) * (w + 1)], w, xi1);
            // Uniform in solid angle inside the pixel: u uniform, cos θ uniform (θ = π v, shaders/envmap.glsl).
            const float u = (c + xi2) / w;
            const float cos0 = std::cos(kPiF * r / h), cos1 = std::cos(kPiF * (r + 1) / h);
            const float v = std::acos(std::clamp(cos0 + (cos1 - cos0) * xi3, -1.0f, 1.0f)) / kPiF;
            d = glsl::envmap_direction(glm::vec2(u, v));
            p = pixel_prob_[static_cast<size_t>(r) * w + c] / glsl::envmap_pixel_solid_angle(float(r), float(w), float(h));
            return glm::max(map_.at(c, r), glm::vec3(0.0f));
        }
        case Kind::srbf: {
            const int j = sample_cdf(light_cdf_.data(), static_cast<int>(lights_.size()), xi0);
            const SrbfLight& l = lights_[j];
            const float cos_g = glsl::srbf_lobe_cos(l.lambda, xi1);
            const float sin_g = std::sqrt(std::max(0.0f, 1.0f - cos_g * cos_g)), phi = 2.0f * kPiF * xi2;
            glm::vec3 b1, b2;
            basis(l.omega, b1, b2);
            d = glm::normalize(cos_g * l.omega + sin_g * (std::cos(phi) * b1 + std::sin(phi) * b2));
            p = pdf(d);
            return evaluate_srbf_lights(lights_, d);
        }
    }
    p = 0;
    return glm::vec3(0.0f);
}

// ───────────────────────── Embree scene ─────────────────────────

void validate(const ReferenceSettings& s) {
    if (s.samples_per_pixel < 1 || s.samples_per_pixel > kMaxReferenceSpp)
        throw Error::parameter("option --spp", "must be in [1, " + std::to_string(kMaxReferenceSpp) + "]");
    if (s.max_depth < 1 || s.max_depth > kMaxReferenceDepth)
        throw Error::parameter("option --max-depth", "must be in [1, " + std::to_string(kMaxReferenceDepth) + "]");
    if (s.roulette_depth < 1) throw Error::parameter("roulette depth", "must be >= 1");
    if (!std::isfinite(s.fiber_radius) || s.fiber_radius < 0) throw Error::parameter("option --radius", "must be a finite number >= 0 (0 = auto)");
    check_finite(s.background, "option --background");
    if (s.threads < 0) throw Error::parameter("option --threads", "must be >= 0 (0 = all hardware threads)");
}

namespace {

struct FilterContext {
    RTCIntersectContext base;  // first member: Embree passes &base back to the filter
    const std::uint32_t* segment_strand = nullptr;
    unsigned skip = RTC_INVALID_GEOMETRY_ID;  // the segment a ray leaves from (with its neighbours on the strand)
};

void skip_own_fibre(const RTCFilterFunctionNArguments* args) {
    const auto* ctx = reinterpret_cast<const FilterContext*>(args->context);
    if (ctx->skip == RTC_INVALID_GEOMETRY_ID) return;
    for (unsigned i = 0; i < args->N; ++i) {
        if (args->valid[i] != -1) continue;
        const unsigned prim = RTCHitN_primID(args->hit, args->N, i);
        const unsigned diff = prim > ctx->skip ? prim - ctx->skip : ctx->skip - prim;
        if (diff <= 1 && ctx->segment_strand[prim] == ctx->segment_strand[ctx->skip]) args->valid[i] = 0;
    }
}

}  // namespace

struct ReferenceRenderer::Impl {
    RTCDevice device = nullptr;
    RTCScene scene = nullptr;
    std::string error;
    ~Impl() {
        if (scene) rtcReleaseScene(scene);
        if (device) rtcReleaseDevice(device);
    }
};

ReferenceRenderer::ReferenceRenderer(const Strands& strands, const ReferenceEnvironment& environment, const FiberBsdf& bsdf,
                                     const ReferenceSettings& settings)
    : env_(environment), bsdf_(bsdf), settings_(settings), impl_(std::make_unique<Impl>()) {
    validate(settings_);
    const auto t0 = std::chrono::steady_clock::now();
    radius_ = settings_.fiber_radius > 0 ? settings_.fiber_radius : auto_fiber_radius(strands);
    if (!(radius_ > 0) || !std::isfinite(radius_)) throw Error::parameter("option --radius", "the fibre radius must be positive");

    impl_->device = rtcNewDevice(nullptr);
    if (!impl_->device) throw Error::parameter("Embree", "cannot create a device (error " + std::to_string(rtcGetDeviceError(nullptr)) + ")");
    rtcSetDeviceErrorFunction(
        impl_->device, [](void* user, RTCError, const char* text) { static_cast<Impl*>(user)->error = text ? text : "unknown"; },
        impl_.get());

    std::size_t n_seg = 0;
    for (std::size_t s = 0; s < strands.strand_count(); ++s) n_seg += strands.point_count(s) - 1;
    if (n_seg == 0) throw Error::parameter("strands", "no segments to render");
    RTCGeometry geom = rtcNewGeometry(impl_->device, RTC_GEOMETRY_TYPE_ROUND_LINEAR_CURVE);
    auto* vertices = static_cast<float*>(
        rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_VERTEX, 0, RTC_FORMAT_FLOAT4, 4 * sizeof(float), strands.points.size()));
    auto* indices = static_cast<unsigned*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_INDEX, 0, RTC_FORMAT_UINT, sizeof(unsigned), n_seg));
    auto* flags = static_cast<unsigned char*>(rtcSetNewGeometryBuffer(geom, RTC_BUFFER_TYPE_FLAGS, 0, RTC_FORMAT_UCHAR, 1, n_seg));
    if (!vertices || !indices || !flags) throw Error::parameter("Embree", "cannot allocate the fibre buffers: " + impl_->error);
    for (std::size_t i = 0; i < strands.points.size(); ++i) {
        vertices[4 * i + 0] = strands.points[i].x;
        vertices[4 * i + 1] = strands.points[i].y;
        vertices[4 * i + 2] = strands.points[i].z;
        vertices[4 * i + 3] = radius_;
    }
    segment_strand_.resize(n_seg);
    segment_tangent_.resize(n_seg);
    std::size_t k = 0;
    for (std::size_t s = 0; s < strands.strand_count(); ++s) {
        const std::uint32_t first = strands.offsets[s], last = strands.offsets[s + 1] - 1;
        for (std::uint32_t p = first; p < last; ++p, ++k) {
            indices[k] = p;
            flags[k] = static_cast<unsigned char>((p > first ? RTC_CURVE_FLAG_NEIGHBOR_LEFT : 0) |
                                                  (p + 1 < last ? RTC_CURVE_FLAG_NEIGHBOR_RIGHT : 0));
            segment_strand_[k] = static_cast<std::uint32_t>(s);
            const glm::vec3 d = strands.points[p + 1] - strands.points[p];
            // Zero-length segments (repeated points) borrow the strand's chord so the frame stays defined.
            segment_tangent_[k] = glm::length(d) > 0 ? glm::normalize(d)
                                                     : glm::normalize(strands.points[last] - strands.points[first]);
        }
    }
    rtcCommitGeometry(geom);
    impl_->scene = rtcNewScene(impl_->device);
    rtcSetSceneFlags(impl_->scene, RTC_SCENE_FLAG_CONTEXT_FILTER_FUNCTION | RTC_SCENE_FLAG_ROBUST);
    rtcSetSceneBuildQuality(impl_->scene, RTC_BUILD_QUALITY_HIGH);
    rtcAttachGeometry(impl_->scene, geom);
    rtcReleaseGeometry(geom);
    rtcCommitScene(impl_->scene);
    if (!impl_->error.empty()) throw Error::parameter("Embree", impl_->error);
    build_seconds_ = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

ReferenceRenderer::~ReferenceRenderer() = default;

// ───────────────────────── the path tracer ─────────────────────────

namespace {

struct Hit {
    bool found = false;
    glm::vec3 position{0.0f};
    unsigned segment = 0;
};

struct Tracer {
    RTCScene scene;
    const std::uint32_t* segment_strand;
    const glm::vec3* segment_tangent;
    const ReferenceEnvironment& env;
    const FiberBsdf& bsdf;
    int max_depth, roulette_depth;
    bool shadows;
    FiberLobeHint hints[3];
    int n_hints = 0;
    float lobe_cdf[4] = {0, 0, 0, 0};
    mutable std::uint64_t rays = 0;

    static constexpr float kUniformShare = 0.2f;  // defensive share of uniform-sphere directions

    FilterContext context(unsigned skip) const {
        FilterContext c;
        rtcInitIntersectContext(&c.base);
        c.base.filter = skip_own_fibre;
        c.segment_strand = segment_strand;
        c.skip = skip;
        return c;
    }

    Hit intersect(const glm::vec3& o, const glm::vec3& d, unsigned skip) const {
        FilterContext ctx = context(skip);
        RTCRayHit rh;
        rh.ray.org_x = o.x, rh.ray.org_y = o.y, rh.ray.org_z = o.z;
        rh.ray.dir_x = d.x, rh.ray.dir_y = d.y, rh.ray.dir_z = d.z;
        rh.ray.tnear = 0.0f;
        rh.ray.tfar = kInf;
        rh.ray.time = 0.0f;
        rh.ray.mask = ~0u;
        rh.ray.id = 0;
        rh.ray.flags = 0;
        rh.hit.geomID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.primID = RTC_INVALID_GEOMETRY_ID;
        rh.hit.instID[0] = RTC_INVALID_GEOMETRY_ID;
        rtcIntersect1(scene, &ctx.base, &rh);
        ++rays;
        Hit h;
        if (rh.hit.geomID == RTC_INVALID_GEOMETRY_ID) return h;
        h.found = true;
        h.position = o + rh.ray.tfar * d;
        h.segment = rh.hit.primID;
        return h;
    }

    bool occluded(const glm::vec3& o, const glm::vec3& d, unsigned skip) const {
        FilterContext ctx = context(skip);
        RTCRay r;
        r.org_x = o.x, r.org_y = o.y, r.org_z = o.z;
        r.dir_x = d.x, r.dir_y = d.y, r.dir_z = d.z;
        r.tnear = 0.0f;
        r.tfar = kInf;
        r.time = 0.0f;
        r.mask = ~0u;
        r.id = 0;
        r.flags = 0;
        rtcOccluded1(scene, &ctx.base, &r);
        ++rays;
        return r.tfar < 0.0f;
    }

    FiberFrame frame(unsigned segment) const {
        const glm::vec3 u = segment_tangent[segment];
        // v: the horizontal normal u × y (eccentric fibres lie with the axis `a` scales horizontal); any
        // normal when the fibre is vertical (FibreFrame picks one).
        return FiberFrame::from_tangent(u, glm::cross(u, glm::vec3(0.0f, 1.0f, 0.0f)));
    }

    static float cos_theta(const FiberFrame& f, const glm::vec3& d) {
        const float s = glm::dot(f.u, d);
        return std::sqrt(std::max(0.0f, 1.0f - s * s));
    }

    static float normal_pdf(float x, float mu, float sigma) {
        const float z = (x - mu) / sigma;
        return std::exp(-0.5f * z * z) / (sigma * 2.5066282746f);
    }
    // Wrapped normal density of φ around mu (three wraps are plenty for σ ≤ 1), or uniform for σ ≥ π.
    static float phi_pdf(float phi, float mu, float sigma) {
        if (sigma >= kPiF) return 1.0f / (2.0f * kPiF);
        float d = phi - mu;
        d -= 2.0f * kPiF * std::floor((d + kPiF) / (2.0f * kPiF));
        return normal_pdf(d, 0.0f, sigma) + normal_pdf(d - 2.0f * kPiF, 0.0f, sigma) + normal_pdf(d + 2.0f * kPiF, 0.0f, sigma);
    }

    // Solid-angle density of the scattering-direction sampler.
    float direction_pdf(const FiberFrame& f, const glm::vec3& wo, const glm::vec3& wi) const {
        float p = (n_hints ? kUniformShare : 1.0f) / (4.0f * kPiF);
        if (!n_hints) return p;
        float theta_o, phi_o, theta_i, phi_i;
        glsl::hair_angles(wo, f.u, f.v, f.w, theta_o, phi_o);
        glsl::hair_angles(wi, f.u, f.v, f.w, theta_i, phi_i);
        const float c = std::cos(theta_i);
        if (c < 1e-6f) return p;
        float lobes = 0;
        for (int l = 0; l < n_hints; ++l) {
            const float w = lobe_cdf[l + 1] - lobe_cdf[l];
            // θi ~ N(2α − θo, σ = √2 β): M_t(θh) = 2 g^u(θi; 2α − θo, 2β) has variance (2β)²/2 (000 eq. 7).
            lobes += w * normal_pdf(theta_i, 2.0f * hints[l].alpha - theta_o, 1.41421356f * hints[l].beta) *
                     phi_pdf(phi_i, phi_o + hints[l].phi_offset, hints[l].phi_sigma);
        }
        return p + (1.0f - kUniformShare) * lobes / c;
    }

    // Draws a scattering direction; false when the draw falls outside the sphere's θ range (the path ends:
    // an unbiased zero contribution).
    bool sample_direction(const FiberFrame& f, const glm::vec3& wo, Pcg32& rng, glm::vec3& wi) const {
        const float xi = rng.uniform();
        if (!n_hints || xi < kUniformShare) {
            wi = uniform_sphere(rng.uniform(), rng.uniform());
            return true;
        }
        const float x = (xi - kUniformShare) / (1.0f - kUniformShare);
        int l = 0;
        while (l + 1 < n_hints && x >= lobe_cdf[l + 1]) ++l;
        float theta_o, phi_o;
        glsl::hair_angles(wo, f.u, f.v, f.w, theta_o, phi_o);
        const float theta_i = 2.0f * hints[l].alpha - theta_o + 1.41421356f * hints[l].beta * rng.normal();
        if (std::abs(theta_i) >= 0.5f * kPiF) return false;
        const float phi_i = hints[l].phi_sigma >= kPiF ? kPiF * (2.0f * rng.uniform() - 1.0f)
                                                      : phi_o + hints[l].phi_offset + hints[l].phi_sigma * rng.normal();
        const float ct = std::cos(theta_i);
        wi = glm::normalize(std::sin(theta_i) * f.u + ct * (std::cos(phi_i) * f.v + std::sin(phi_i) * f.w));
        return true;
    }

    static float power_heuristic(float a, float b) { return a * a / (a * a + b * b); }

    // Radiance leaving the fibre at `hit` towards −d (d = the direction of the ray that found it).
    glm::vec3 radiance(Hit hit, glm::vec3 d, Pcg32& rng) const {
        glm::vec3 L(0.0f), throughput(1.0f);
        for (int depth = 1;; ++depth) {
            const FiberFrame f = frame(hit.segment);
            const glm::vec3 wo = -d;
            // Next-event estimation of the environment.
            {
                glm::vec3 wi;
                float p_light = 0;
                const float x0 = rng.uniform(), x1 = rng.uniform(), x2 = rng.uniform(), x3 = rng.uniform();
                const glm::vec3 Le = env.sample(x0, x1, x2, x3, wi, p_light);
                if (p_light > 0 && max3(Le) > 0) {
                    const glm::vec3 fs = bsdf.S(f, wi, wo) * cos_theta(f, wi);
                    if (max3(fs) > 0 && !(shadows && occluded(hit.position, wi, hit.segment))) {
                        const float w = power_heuristic(p_light, direction_pdf(f, wo, wi));
                        L += throughput * fs * Le * (w / p_light);
                    }
                }
            }
            // Scattering-direction sampling: counts the environment (MIS) and continues the path.
            glm::vec3 wi;
            if (!sample_direction(f, wo, rng, wi)) break;
            const float p_dir = direction_pdf(f, wo, wi);
            if (!(p_dir > 0)) break;
            const glm::vec3 fs = bsdf.S(f, wi, wo) * cos_theta(f, wi);
            if (!(max3(fs) > 0)) break;
            throughput *= fs / p_dir;
            const Hit next = intersect(hit.position, wi, hit.segment);
            if (!next.found || !shadows) {  // without shadows the environment reaches through other fibres
                const float w = power_heuristic(p_dir, env.pdf(wi));
                L += throughput * env.radiance(wi) * w;
            }
            if (!next.found) break;
            if (depth >= max_depth) break;
            if (depth >= roulette_depth) {
                const float q = std::min(0.95f, max3(throughput));
                if (!(rng.uniform() < q)) break;
                throughput /= q;
            }
            hit = next;
            d = wi;
        }
        return L;
    }
};

Tracer make_tracer(RTCScene scene, const std::vector<std::uint32_t>& strand, const std::vector<glm::vec3>& tangent,
                   const ReferenceEnvironment& env, const FiberBsdf& bsdf, const ReferenceSettings& s) {
    Tracer t{scene, strand.data(), tangent.data(), env, bsdf, s.max_depth, s.roulette_depth, s.shadows, {}, 0, {}, 0};
    t.n_hints = bsdf.lobe_hints(t.hints);
    float total = 0;
    for (int l = 0; l < t.n_hints; ++l) total += std::max(0.0f, t.hints[l].weight);
    for (int l = 0; l < t.n_hints; ++l) t.lobe_cdf[l + 1] = t.lobe_cdf[l] + std::max(0.0f, t.hints[l].weight) / total;
    return t;
}

}  // namespace

glm::vec4 ReferenceRenderer::trace(const glm::vec3& origin, const glm::vec3& direction, int paths, std::uint64_t seed) const {
    const Tracer tracer = make_tracer(impl_->scene, segment_strand_, segment_tangent_, env_, bsdf_, settings_);
    const glm::vec3 d = glm::normalize(direction);
    glm::dvec3 sum(0.0);
    int hits = 0;
    for (int i = 0; i < paths; ++i) {
        Pcg32 rng(seed, static_cast<std::uint64_t>(i));
        const Hit h = tracer.intersect(origin, d, RTC_INVALID_GEOMETRY_ID);
        if (!h.found) continue;
        ++hits;
        sum += glm::dvec3(tracer.radiance(h, d, rng));
    }
    return hits ? glm::vec4(glm::vec3(sum / double(hits)), float(hits) / float(paths)) : glm::vec4(0.0f);
}

ReferenceRenderer::LitHit ReferenceRenderer::first_fibre_lit(const glm::vec3& origin, const glm::vec3& direction,
                                                              const glm::vec3& light) const {
    const Tracer tracer = make_tracer(impl_->scene, segment_strand_, segment_tangent_, env_, bsdf_, settings_);
    const Hit h = tracer.intersect(origin, glm::normalize(direction), RTC_INVALID_GEOMETRY_ID);
    LitHit out;
    if (!h.found) return out;
    out.found = true;
    out.position = h.position;
    out.lit = !tracer.occluded(h.position, glm::normalize(light), h.segment);
    return out;
}

Image ReferenceRenderer::render(const Camera& camera, ReferenceStats* stats) const {
    if (camera.width < 1 || camera.height < 1 || camera.width > kMaxImageSide || camera.height > kMaxImageSide)
        throw Error::parameter("camera", "image size " + std::to_string(camera.width) + "x" + std::to_string(camera.height) +
                                             " is outside [1, " + std::to_string(kMaxImageSide) + "]");
    const int w = camera.width, h = camera.height, spp = settings_.samples_per_pixel;
    Image image(w, h, settings_.alpha ? 4 : 3);
    std::unique_ptr<Progress> bar;
    if (settings_.progress) bar = std::make_unique<Progress>("reference " + std::to_string(spp) + " spp", static_cast<std::uint64_t>(h));
    std::atomic<std::uint64_t> total_rays{0};
    std::atomic<std::uint64_t> total_hits{0};
    const auto t0 = std::chrono::steady_clock::now();
    // One row per task; every pixel draws from its own Pcg32 stream (seed, pixel index), so rows may run in
    // any order and the image is the same on any thread count.
    parallel_for(static_cast<std::size_t>(h), settings_.threads, [&](std::size_t row) {
        const int y = static_cast<int>(row);
        const Tracer tracer = make_tracer(impl_->scene, segment_strand_, segment_tangent_, env_, bsdf_, settings_);
        std::uint64_t hits_here = 0;
        for (int x = 0; x < w; ++x) {
            Pcg32 rng(settings_.seed, static_cast<std::uint64_t>(y) * w + x);
            glm::dvec3 hair(0.0), background(0.0);
            int hits = 0;
            for (int s = 0; s < spp; ++s) {
                glm::vec3 o, d;
                camera.ray(x + rng.uniform(), y + rng.uniform(), o, d);
                const Hit hit = tracer.intersect(o, d, RTC_INVALID_GEOMETRY_ID);
                if (hit.found) {
                    ++hits;
                    hair += glm::dvec3(tracer.radiance(hit, d, rng));
                } else {
                    background += glm::dvec3(settings_.background_env ? env_.radiance(d) : settings_.background);
                }
            }
            hits_here += hits;
            float* p = image.at(x, y);
            if (settings_.alpha) {
                const glm::dvec3 c = hits ? hair / double(hits) : glm::dvec3(0.0);
                p[0] = float(c.x), p[1] = float(c.y), p[2] = float(c.z), p[3] = float(hits) / float(spp);
            } else {
                const glm::dvec3 c = (hair + background) / double(spp);
                p[0] = float(c.x), p[1] = float(c.y), p[2] = float(c.z);
            }
        }
        if (bar) bar->advance(1);
        total_rays += tracer.rays;
        total_hits += hits_here;
    });
    if (bar) bar->finish();
    for (float v : image.pixels)
        if (!std::isfinite(v)) throw Error::parameter("reference render", "a pixel came out NaN or infinite (a bug: please report it)");
    if (stats) {
        stats->build_seconds = build_seconds_;
        stats->render_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
        stats->camera_rays = static_cast<std::uint64_t>(w) * h * spp;
        stats->rays = total_rays;
        stats->samples_per_pixel = spp;
        stats->fiber_radius = radius_;
        stats->segments = segment_strand_.size();
        stats->coverage = double(total_hits) / double(stats->camera_rays);
    }
    return image;
}

}  // namespace coif
