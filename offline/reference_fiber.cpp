#include "offline/reference_fiber.h"

#include <algorithm>
#include <cmath>
#include <vector>

#include "models/core/error.h"
#include "models/core/parallel.h"
#include "models/core/units.h"
#include "shaders/hair_parameters.h"
#include "shaders/marschner_reference.h"

namespace coif {
namespace {

// x wrapped to [−π, π).
float wrap_pi(float x) { return x - 2.0f * kPiF * std::floor((x + kPiF) / (2.0f * kPiF)); }

// Longitudinal angle θ and azimuth φ of a unit direction in the hair frame, by the lighting module's
// own convention (srbf_single.glsl hair_angles).
void angles(const FiberFrame& f, const glm::vec3& d, float& theta, float& phi) {
    glsl::hair_angles(d, f.u, f.v, f.w, theta, phi);
}

}  // namespace

glm::vec3 IsotropicFiber::S(const FiberFrame&, const glm::vec3&, const glm::vec3&) const {
    return albedo_ / (kPiF * kPiF);
}

// ───────────────────────── the exact azimuthal functions, tabulated ─────────────────────────
//
// N_t(θd, φ) comes from the lighting module's exact reference (shading::reference::N_exact: sum over the
// roots of 000 eq. 8–9 with exact Fresnel; TRT roughened by w_c). That function integrates or root-finds
// per call (≈0.1 ms), far too slow for the millions of evaluations of a render, so MarschnerFiber samples
// it once per parameter set on a grid and interpolates (trilinear in |θd|, |φ| and, for eccentric TRT,
// η*). N is even in θd (η', σa' and the Fresnel term depend on cos θd and sin² θd) and in φ (h ↦ −h), so
// the grid covers |θd| ∈ [0, π/2] and |φ| ∈ [0, π]. The interpolation error is measured by the tests
// (test_reference.cpp, FiberTableMatchesTheExactModel).
struct MarschnerTable {
    static constexpr int kTheta = 32;   // |θd| steps of 2.9°
    static constexpr int kPhi = 129;    // |φ| steps of 1.4°; the narrowest lobe (TRT at w_c = 0.15 rad) spans ~12 steps
    static constexpr int kEtaEcc = 9;   // η* samples of eccentric TRT over [η*_min, η*_max] (000 eq. 24)
    static constexpr float kThetaMax = 0.5f * kPiF * 0.999f;
    int n_eta = 1;
    float eta_lo = 0, eta_hi = 0;
    // [lobe][η index][θ index][φ index]
    std::vector<glm::vec3> values;

    size_t index(int lobe, int e, int t, int p) const {
        return ((static_cast<size_t>(lobe) * n_eta + e) * kTheta + t) * kPhi + p;
    }
    glm::vec3 lookup(int lobe, float eta_star, float theta_d, float phi) const {
        const float ft = std::min(std::abs(theta_d), kThetaMax) / kThetaMax * (kTheta - 1);
        const float fp = std::min(std::abs(wrap_pi(phi)), kPiF) / kPiF * (kPhi - 1);
        const int t0 = std::min(static_cast<int>(ft), kTheta - 2), p0 = std::min(static_cast<int>(fp), kPhi - 2);
        const float st = ft - t0, sp = fp - p0;
        int e0 = 0;
        float se = 0;
        if (lobe == glsl::LOBE_TRT && n_eta > 1) {
            const float fe = std::clamp((eta_star - eta_lo) / (eta_hi - eta_lo), 0.0f, 1.0f) * (n_eta - 1);
            e0 = std::min(static_cast<int>(fe), n_eta - 2);
            se = fe - e0;
        }
        const int le = lobe == glsl::LOBE_TRT ? n_eta : 1;
        glm::vec3 r(0.0f);
        for (int de = 0; de < (le > 1 ? 2 : 1); ++de) {
            const float we = le > 1 ? (de ? se : 1.0f - se) : 1.0f;
            const int e = e0 + de;
            const glm::vec3 a = values[index(lobe, e, t0, p0)], b = values[index(lobe, e, t0, p0 + 1)];
            const glm::vec3 c = values[index(lobe, e, t0 + 1, p0)], d = values[index(lobe, e, t0 + 1, p0 + 1)];
            r += we * ((1 - st) * ((1 - sp) * a + sp * b) + st * ((1 - sp) * c + sp * d));
        }
        return r;
    }
};

namespace {

float table_theta(int t) { return MarschnerTable::kThetaMax * t / (MarschnerTable::kTheta - 1); }
float table_phi(int p) { return kPiF * p / (MarschnerTable::kPhi - 1); }

std::shared_ptr<MarschnerTable> build_table(const shading::HairParams& hp) {
    auto table = std::make_shared<MarschnerTable>();
    const bool eccentric = hp.ecc_a != 1.0f;
    table->n_eta = eccentric ? MarschnerTable::kEtaEcc : 1;
    table->eta_lo = std::min(glsl::eta_star_1(hp.eta, hp.ecc_a), glsl::eta_star_2(hp.eta, hp.ecc_a));
    table->eta_hi = std::max(glsl::eta_star_1(hp.eta, hp.ecc_a), glsl::eta_star_2(hp.eta, hp.ecc_a));
    // R and TT use η; TRT uses η* (= η when a = 1), so lobes R, TT hold one η slice each and TRT n_eta.
    table->values.assign(static_cast<size_t>(shading::kLobeCount) * table->n_eta * MarschnerTable::kTheta * MarschnerTable::kPhi, glm::vec3(0.0f));
    struct Job {
        int lobe, e, t;
    };
    std::vector<Job> jobs;
    for (int lobe = 0; lobe < shading::kLobeCount; ++lobe)
        for (int e = 0; e < (lobe == glsl::LOBE_TRT ? table->n_eta : 1); ++e)
            for (int t = 0; t < MarschnerTable::kTheta; ++t) jobs.push_back({lobe, e, t});
    parallel_for(jobs.size(), 0, [&](size_t j) {
        const Job& job = jobs[j];
        const double eta = job.lobe == glsl::LOBE_TRT && table->n_eta > 1
                               ? table->eta_lo + (table->eta_hi - table->eta_lo) * job.e / (table->n_eta - 1)
                               : double(hp.eta);
        for (int p = 0; p < MarschnerTable::kPhi; ++p)
            table->values[table->index(job.lobe, job.e, job.t, p)] =
                glm::vec3(shading::reference::N_exact(job.lobe, hp, eta, table_theta(job.t), table_phi(p)));
    });
    return table;
}

}  // namespace

MarschnerFiber::MarschnerFiber(const shading::HairParams& params) : params_(params) {
    shading::validate(params_, "hair parameters");
    table_ = build_table(params_);
}

glm::vec3 MarschnerFiber::N(int lobe, float eta_star, float theta_d, float phi) const {
    return table_->lookup(lobe, eta_star, theta_d, phi);
}

glm::vec3 MarschnerFiber::S(const FiberFrame& frame, const glm::vec3& wi, const glm::vec3& wo) const {
    float theta_i, phi_i, theta_o, phi_o;
    angles(frame, wi, theta_i, phi_i);
    angles(frame, wo, theta_o, phi_o);
    const float theta_d = 0.5f * (theta_o - theta_i);
    const float phi = phi_o - phi_i;
    const float cos_d = std::cos(theta_d);
    const float inv_cos2 = 1.0f / std::max(cos_d * cos_d, 1e-6f);
    // Eccentric TRT: η*(φh) with cos 2φh = cos(φi + φo) (000 eq. 24; marschner_reference.h).
    const float eta_trt = params_.ecc_a != 1.0f ? glsl::eta_star(params_.eta, params_.ecc_a, std::cos(phi_i + phi_o)) : params_.eta;
    glm::vec3 s(0.0f);
    for (int lobe = 0; lobe < shading::kLobeCount; ++lobe) {
        // 000 eq. 6: S_t = M_t(θh) N_t(η, θd, φ) / cos² θd.
        const float m = glsl::M_lobe(params_, lobe, theta_i, theta_o);
        if (m < 1e-12f) continue;
        s += m * table_->lookup(lobe, eta_trt, theta_d, phi);
    }
    return s * inv_cos2;
}

int MarschnerFiber::lobe_hints(FiberLobeHint out[3]) const {
    // R and TRT spread over every azimuth (N_R ∝ |cos(φ/2)|, TRT has glints off-centre); TT is forward, at
    // φ = φo − φi ≈ π, so φi ≈ φo − π.
    out[0] = {params_.alpha_R, params_.beta_R, 0.0f, 10.0f, 0.3f};
    out[1] = {params_.alpha_TT, params_.beta_TT, -kPiF, 0.6f, 0.45f};
    out[2] = {params_.alpha_TRT, params_.beta_TRT, 0.0f, 10.0f, 0.25f};
    return 3;
}

glm::vec3 fiber_albedo(const FiberBsdf& bsdf, const FiberFrame& frame, const glm::vec3& wo, int n) {
    // ∫ S cos θi dωi with dωi = d(sin θi) dφi: midpoint rule on n × 2n cells of (sin θi, φi).
    glm::dvec3 acc(0.0);
    const double ds = 2.0 / n, dphi = kPiF / n;
    for (int i = 0; i < n; ++i) {
        const double s = -1.0 + (i + 0.5) * ds, c = std::sqrt(std::max(0.0, 1.0 - s * s));
        for (int j = 0; j < 2 * n; ++j) {
            const double phi = -kPiF + (j + 0.5) * dphi;
            const glm::vec3 wi = glm::normalize(float(s) * frame.u + float(c * std::cos(phi)) * frame.v + float(c * std::sin(phi)) * frame.w);
            acc += glm::dvec3(bsdf.S(frame, wi, wo)) * c;
        }
    }
    return glm::vec3(acc * ds * dphi);
}

}  // namespace coif
