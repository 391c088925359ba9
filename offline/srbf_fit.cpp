#include "offline/srbf_fit.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <memory>
#include <numeric>

#include <ceres/ceres.h>

#include "models/core/error.h"
#include "models/core/random.h"
#include "models/core/units.h"
#include "shaders/envmap.h"

namespace coif {

namespace {

// Pixels of the fit grid, flattened. The model's value for a pixel is its box-filtered average over the
// pixel (s × s sub-samples weighted by their solid angle), matching the downsampled map, which is the
// box-filtered original: a light narrower than a pixel then keeps its energy instead of being fitted
// at the pixel centre by a too-bright lobe (point sampling overestimates a sub-pixel source's energy
// about 2×: ∫G / ∫G² for a lobe of the pixel's size).
struct FitPixels {
    int samples = 0;                    // sub-samples per pixel (s²)
    std::vector<glm::dvec3> sub_omega;  // pixel p's sub-sample k: [p * samples + k]
    std::vector<double> sub_weight;     // sums to 1 over a pixel
    std::vector<glm::dvec3> omega;      // pixel centre direction
    std::vector<double> sqrt_d_omega;   // the residual weight
    std::vector<glm::dvec3> target;     // radiance / scale
    std::vector<double> energy;         // luminance × solid angle (clustering weight)
};

FitPixels fit_pixels(const EnvMap& map, double scale, int s) {
    FitPixels px;
    px.samples = s * s;
    const size_t n = map.radiance.size();
    px.omega.reserve(n), px.sqrt_d_omega.reserve(n), px.target.reserve(n), px.energy.reserve(n);
    px.sub_omega.reserve(n * px.samples), px.sub_weight.reserve(n * px.samples);
    const float sub_w = float(map.width * s), sub_h = float(map.height * s);
    for (int row = 0; row < map.height; ++row) {
        const double d_omega = map.pixel_solid_angle(row);
        double row_weight = 0.0;
        std::vector<double> w_b(s);
        for (int b = 0; b < s; ++b) row_weight += w_b[b] = glsl::envmap_pixel_solid_angle(float(row * s + b), sub_w, sub_h);
        for (int col = 0; col < map.width; ++col) {
            for (int b = 0; b < s; ++b)
                for (int a = 0; a < s; ++a) {
                    const glm::vec2 uv((float(col * s + a) + 0.5f) / sub_w, (float(row * s + b) + 0.5f) / sub_h);
                    px.sub_omega.push_back(glm::normalize(glm::dvec3(glsl::envmap_direction(uv))));
                    px.sub_weight.push_back(w_b[b] / (row_weight * s));
                }
            px.omega.push_back(glm::normalize(glm::dvec3(map.direction(col, row))));
            px.sqrt_d_omega.push_back(std::sqrt(d_omega));
            const glm::dvec3 L = glm::dvec3(map.at(col, row)) / scale;
            px.target.push_back(L);
            px.energy.push_back(std::max(0.0, luminance(L)) * d_omega);
        }
    }
    return px;
}

// Below this exponent G = e^{2(d−1)/λ²} < 1e-17 and it and its derivatives are dropped: far under double
// rounding of any residual that the light could matter to.
constexpr double kNegligibleExponent = -40.0;

// One residual block holding every pixel: r_{3p+c} = sqrt(ΔΩ_p) (Σ_j L_jc Ḡ_j(p) − L_c(p)), where
// Ḡ_j(p) = Σ_k w_k G(ω_k; ω_j, λ_j) is the SRBF averaged over pixel p's sub-samples.
// Parameter blocks, per light j: L_j (3), ω_j (3, on the sphere), λ_j (1). Analytic Jacobian:
//   ∂r_c/∂L_jc = W Ḡ,   ∂r_c/∂ω_j = W L_jc Σ_k w_k G_k (2/λ²) ω_k,   ∂r_c/∂λ_j = W L_jc Σ_k w_k G_k (−4(ω_k·ω_j − 1)/λ³).
// One block (rather than one per pixel) keeps Ceres's per-block overhead out of a dense problem.
class SrbfMapCost final : public ceres::CostFunction {
public:
    SrbfMapCost(const FitPixels& px, int n_lights) : px_(px), n_lights_(n_lights) {
        set_num_residuals(int(3 * px.omega.size()));
        for (int j = 0; j < n_lights; ++j) {
            mutable_parameter_block_sizes()->push_back(3);
            mutable_parameter_block_sizes()->push_back(3);
            mutable_parameter_block_sizes()->push_back(1);
        }
    }

    bool Evaluate(double const* const* parameters, double* residuals, double** jacobians) const override {
        const size_t n_px = px_.omega.size();
        const int n_res = int(3 * n_px);
        const int S = px_.samples;
        if (jacobians)
            for (int j = 0; j < n_lights_; ++j)
                for (int b = 0; b < 3; ++b)
                    if (double* J = jacobians[3 * j + b]) std::fill(J, J + size_t(n_res) * (b == 2 ? 1 : 3), 0.0);
        for (size_t p = 0; p < n_px; ++p) {
            const double weight = px_.sqrt_d_omega[p];
            const glm::dvec3* sub_omega = &px_.sub_omega[p * S];
            const double* sub_weight = &px_.sub_weight[p * S];
            glm::dvec3 sum(0.0);
            for (int j = 0; j < n_lights_; ++j) {
                const double* L = parameters[3 * j];
                const glm::dvec3 o(parameters[3 * j + 1][0], parameters[3 * j + 1][1], parameters[3 * j + 1][2]);
                const double lambda = parameters[3 * j + 2][0];
                const double inv_l2 = 1.0 / (lambda * lambda);
                double G_bar = 0.0, dlambda = 0.0;
                glm::dvec3 domega(0.0);
                for (int k = 0; k < S; ++k) {
                    const double d_minus_1 = glm::dot(sub_omega[k], o) - 1.0;
                    const double exponent = 2.0 * d_minus_1 * inv_l2;
                    if (exponent < kNegligibleExponent) continue;
                    const double wG = sub_weight[k] * std::exp(exponent);
                    G_bar += wG;
                    if (jacobians) {
                        domega += wG * sub_omega[k];
                        dlambda += wG * d_minus_1;
                    }
                }
                if (G_bar == 0.0) continue;
                sum += G_bar * glm::dvec3(L[0], L[1], L[2]);
                if (!jacobians) continue;
                domega *= weight * 2.0 * inv_l2;
                dlambda *= weight * -4.0 * inv_l2 / lambda;
                if (double* J = jacobians[3 * j])
                    for (int c = 0; c < 3; ++c) J[(3 * p + c) * 3 + c] = weight * G_bar;
                if (double* J = jacobians[3 * j + 1])
                    for (int c = 0; c < 3; ++c) {
                        J[(3 * p + c) * 3 + 0] = L[c] * domega.x;
                        J[(3 * p + c) * 3 + 1] = L[c] * domega.y;
                        J[(3 * p + c) * 3 + 2] = L[c] * domega.z;
                    }
                if (double* J = jacobians[3 * j + 2])
                    for (int c = 0; c < 3; ++c) J[3 * p + c] = L[c] * dlambda;
            }
            const glm::dvec3 r = weight * (sum - px_.target[p]);
            residuals[3 * p] = r.x, residuals[3 * p + 1] = r.y, residuals[3 * p + 2] = r.z;
        }
        return true;
    }

private:
    const FitPixels& px_;
    int n_lights_;
};

class ProgressCallback final : public ceres::IterationCallback {
public:
    ProgressCallback(const SrbfFitProgress& progress, int max_iterations)
        : progress_(progress), max_iterations_(max_iterations) {}
    ceres::CallbackReturnType operator()(const ceres::IterationSummary& summary) override {
        if (progress_) progress_(summary.iteration, max_iterations_);
        return ceres::SOLVER_CONTINUE;
    }

private:
    const SrbfFitProgress& progress_;
    int max_iterations_;
};

// Index drawn with probability ∝ weight[i] (weights ≥ 0, sum > 0).
size_t draw(const std::vector<double>& weight, Rng& rng) {
    const double total = std::accumulate(weight.begin(), weight.end(), 0.0);
    double x = uniform01(rng) * total;
    for (size_t i = 0; i < weight.size(); ++i) {
        x -= weight[i];
        if (x < 0.0) return i;
    }
    // Rounding left x ≥ 0: the last index with a positive weight.
    for (size_t i = weight.size(); i-- > 0;)
        if (weight[i] > 0) return i;
    return 0;
}

struct Cluster {
    glm::dvec3 omega;
    double lambda;
    glm::dvec3 energy;   // Σ (radiance / scale) ΔΩ over the cluster's pixels
};

// Weighted spherical k-means of the pixels' energy, k-means++ seeding (distance: chord² = 2(1 − ω·c)).
std::vector<Cluster> cluster_energy(const FitPixels& px, int k, std::uint64_t seed, int iterations,
                                    double lambda_min, double lambda_max) {
    const size_t n = px.omega.size();
    Rng rng = seeded_rng(seed);
    std::vector<glm::dvec3> centre;
    std::vector<double> d2(n, 4.0), w(n);
    auto chord2 = [](const glm::dvec3& a, const glm::dvec3& b) { return std::max(0.0, 2.0 * (1.0 - glm::dot(a, b))); };
    for (int c = 0; c < k; ++c) {
        for (size_t i = 0; i < n; ++i) w[i] = px.energy[i] * d2[i];
        size_t pick;
        if (std::accumulate(w.begin(), w.end(), 0.0) > 0.0) {
            pick = draw(w, rng);
        } else {
            // All energy is already on a centre: spread the remaining centres over the sphere.
            for (size_t i = 0; i < n; ++i) w[i] = d2[i];
            pick = draw(w, rng);
        }
        centre.push_back(px.omega[pick]);
        for (size_t i = 0; i < n; ++i) d2[i] = std::min(d2[i], chord2(px.omega[i], centre.back()));
    }

    std::vector<int> label(n, 0);
    for (int it = 0; it <= iterations; ++it) {
        for (size_t i = 0; i < n; ++i) {
            double best = 1e300;
            for (int c = 0; c < k; ++c) {
                const double d = chord2(px.omega[i], centre[c]);
                if (d < best) best = d, label[i] = c;
            }
        }
        if (it == iterations) break;
        std::vector<glm::dvec3> sum(k, glm::dvec3(0.0));
        std::vector<double> mass(k, 0.0);
        for (size_t i = 0; i < n; ++i) sum[label[i]] += px.energy[i] * px.omega[i], mass[label[i]] += px.energy[i];
        for (int c = 0; c < k; ++c)
            if (mass[c] > 0.0 && glm::length(sum[c]) > 1e-12 * mass[c]) centre[c] = glm::normalize(sum[c]);
    }

    std::vector<Cluster> clusters(k);
    std::vector<double> mass(k, 0.0), spread(k, 0.0);
    for (int c = 0; c < k; ++c) clusters[c] = {centre[c], 0.0, glm::dvec3(0.0)};
    for (size_t i = 0; i < n; ++i) {
        const int c = label[i];
        const double d_omega = px.sqrt_d_omega[i] * px.sqrt_d_omega[i];
        clusters[c].energy += px.target[i] * d_omega;
        mass[c] += px.energy[i];
        spread[c] += px.energy[i] * chord2(px.omega[i], centre[c]);
    }
    // G ≈ exp(−chord²/λ²) is a 2D Gaussian whose mean chord² is λ²: match the cluster's second moment.
    for (int c = 0; c < k; ++c) {
        const double lambda = mass[c] > 0.0 ? std::sqrt(spread[c] / mass[c]) : lambda_max;
        clusters[c].lambda = std::clamp(lambda, lambda_min, lambda_max);
    }
    return clusters;
}

const char* termination_name(ceres::TerminationType t) {
    switch (t) {
        case ceres::CONVERGENCE: return "CONVERGENCE";
        case ceres::NO_CONVERGENCE: return "NO_CONVERGENCE (iteration limit)";
        case ceres::FAILURE: return "FAILURE";
        case ceres::USER_SUCCESS: return "USER_SUCCESS";
        case ceres::USER_FAILURE: return "USER_FAILURE";
    }
    return "?";
}

}  // namespace

SrbfFitResult fit_srbf_lights(const EnvMap& map, const SrbfFitSettings& settings, const SrbfFitProgress& progress) {
    const auto start = std::chrono::steady_clock::now();
    if (settings.fit_width % 2 != 0 || settings.fit_width < kMinEnvMapWidth || settings.fit_width > map.width)
        throw Error::parameter("option --fit-width", std::to_string(settings.fit_width) + " must be even and within " +
                                                         std::to_string(kMinEnvMapWidth) + ".." +
                                                         std::to_string(map.width) + " (the map's width)");
    const EnvMap grid = downsample_envmap(map, settings.fit_width);
    const int n_pixels = grid.width * grid.height;
    // Each light has 7 unknowns and each pixel gives 3 equations: keep the problem well overdetermined.
    const int max_lights = std::min(kMaxSrbfLights, n_pixels / 4);
    if (settings.lights < 1 || settings.lights > max_lights)
        throw Error::parameter("option --lights", std::to_string(settings.lights) + " lights: expected 1.." +
                                                      std::to_string(max_lights) + " for a " +
                                                      std::to_string(grid.width) + "x" +
                                                      std::to_string(grid.height) + " fit grid");
    const double lambda_min = settings.lambda_min > 0 ? settings.lambda_min : kPi / (grid.height * settings.supersampling);
    const double lambda_max = settings.lambda_max;
    if (!(lambda_min >= kSrbfLambdaMinAllowed && lambda_max <= kSrbfLambdaMaxAllowed && lambda_min < lambda_max))
        throw Error::parameter("bandwidth range", "[" + std::to_string(lambda_min) + ", " + std::to_string(lambda_max) +
                                                      "] must lie in [" + std::to_string(kSrbfLambdaMinAllowed) + ", " +
                                                      std::to_string(kSrbfLambdaMaxAllowed) + "] with min < max");
    if (settings.supersampling < 1 || settings.supersampling > kMaxSrbfSupersampling)
        throw Error::parameter("supersampling", "must be within 1.." + std::to_string(kMaxSrbfSupersampling));
    if (settings.max_iterations < 1) throw Error::parameter("option --max-iterations", "must be at least 1");

    // Work in units of the map's mean luminance so that the solver's tolerances mean the same for every map.
    const double scale = envmap_mean_luminance(grid);
    const FitPixels px = fit_pixels(grid, scale, settings.supersampling);
    const int N = settings.lights;
    const std::vector<Cluster> clusters =
        cluster_energy(px, N, settings.seed, settings.kmeans_iterations, lambda_min, lambda_max);

    std::vector<double> params(size_t(N) * 7);
    for (int j = 0; j < N; ++j) {
        double* L = &params[7 * j];
        double* o = L + 3;
        const Cluster& c = clusters[j];
        const double integral = glsl::srbf_integral(float(c.lambda));
        for (int k = 0; k < 3; ++k) L[k] = std::max(0.0, c.energy[k] / integral), o[k] = c.omega[k];
        L[6] = c.lambda;  // λ_j sits right after ω_j
    }

    ceres::Problem::Options problem_options;
    problem_options.manifold_ownership = ceres::DO_NOT_TAKE_OWNERSHIP;
    ceres::Problem problem(problem_options);
    ceres::SphereManifold<3> sphere;
    std::vector<double*> blocks;
    for (int j = 0; j < N; ++j) {
        double* base = &params[7 * j];
        blocks.insert(blocks.end(), {base, base + 3, base + 6});
    }
    problem.AddResidualBlock(new SrbfMapCost(px, N), nullptr, blocks);
    for (int j = 0; j < N; ++j) {
        double* base = &params[7 * j];
        problem.SetManifold(base + 3, &sphere);
        for (int k = 0; k < 3; ++k) problem.SetParameterLowerBound(base, k, 0.0);
        problem.SetParameterLowerBound(base + 6, 0, lambda_min);
        problem.SetParameterUpperBound(base + 6, 0, lambda_max);
    }

    ceres::Solver::Options options;
    options.linear_solver_type = ceres::DENSE_NORMAL_CHOLESKY;
    options.num_threads = 1;  // bit-identical results for a seed
    options.logging_type = ceres::SILENT;
    options.minimizer_progress_to_stdout = false;
    options.function_tolerance = 1e-6;
    options.parameter_tolerance = 1e-8;
    // With bounds, Ceres follows every trust-region step by a projected line search that costs one more
    // Jacobian per iteration; the step is projected onto the bounds anyway, and without the search the
    // fits converge to the same error in ~60 % of the time (measured on the four shared maps).
    options.max_num_line_search_step_size_iterations = 0;
    // LAPACK (Debian's ATLAS/OpenBLAS) forms JᵀJ ~1.4× faster than Eigen here.
    if (ceres::IsDenseLinearAlgebraLibraryTypeAvailable(ceres::LAPACK))
        options.dense_linear_algebra_library_type = ceres::LAPACK;

    // Pass 1: amplitudes only (linear least squares under L ≥ 0) for the clustered centres and bandwidths.
    for (int j = 0; j < N; ++j) problem.SetParameterBlockConstant(&params[7 * j + 3]),
                                problem.SetParameterBlockConstant(&params[7 * j + 6]);
    options.max_num_iterations = 20;
    ceres::Solver::Summary summary;
    ceres::Solve(options, &problem, &summary);

    // Pass 2: everything.
    for (int j = 0; j < N; ++j) problem.SetParameterBlockVariable(&params[7 * j + 3]),
                                problem.SetParameterBlockVariable(&params[7 * j + 6]);
    ProgressCallback callback(progress, settings.max_iterations);
    options.callbacks.push_back(&callback);
    options.max_num_iterations = settings.max_iterations;
    ceres::Solve(options, &problem, &summary);

    SrbfFitResult result;
    for (int j = 0; j < N; ++j) {
        const double* p = &params[7 * j];
        SrbfLight light;
        light.L = glm::vec3(glm::dvec3(p[0], p[1], p[2]) * scale);
        light.omega = glm::vec3(glm::normalize(glm::dvec3(p[3], p[4], p[5])));
        light.lambda = float(p[6]);
        result.lights.push_back(light);
    }
    std::stable_sort(result.lights.begin(), result.lights.end(), [](const SrbfLight& a, const SrbfLight& b) {
        return luminance(a.L) * glsl::srbf_integral(a.lambda) > luminance(b.L) * glsl::srbf_integral(b.lambda);
    });

    SrbfFitRecord& rec = result.record;
    rec.lights = N;
    rec.seed = settings.seed;
    rec.fit_width = grid.width;
    rec.lambda_min = lambda_min;
    rec.lambda_max = lambda_max;
    rec.max_iterations = settings.max_iterations;
    rec.iterations = int(summary.iterations.size()) - 1;
    rec.termination = termination_name(summary.termination_type);
    rec.supersampling = settings.supersampling;
    // On the fit grid the model is the box-filtered one the solver minimised: read the error off its cost.
    double target2 = 0.0;
    for (size_t p = 0; p < px.target.size(); ++p)
        target2 += px.sqrt_d_omega[p] * px.sqrt_d_omega[p] * glm::dot(px.target[p], px.target[p]);
    rec.relative_l2_error_fit_grid = std::sqrt(2.0 * summary.final_cost / target2);
    const SrbfFitError full = measure_srbf_fit(map, result.lights);
    rec.relative_l2_error = full.relative_l2;
    rec.energy_error = full.energy;
    rec.energy_error_rgb = full.energy_rgb;
    rec.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
    return result;
}

SrbfFitError measure_srbf_fit(const EnvMap& map, std::span<const SrbfLight> lights) {
    double err2 = 0.0, ref2 = 0.0;
    for (int row = 0; row < map.height; ++row) {
        const double d_omega = map.pixel_solid_angle(row);
        double row_err = 0.0, row_ref = 0.0;
        for (int col = 0; col < map.width; ++col) {
            const glm::dvec3 ref(map.at(col, row));
            const glm::dvec3 fit(evaluate_srbf_lights(lights, map.direction(col, row)));
            row_err += glm::dot(fit - ref, fit - ref);
            row_ref += glm::dot(ref, ref);
        }
        err2 += d_omega * row_err;
        ref2 += d_omega * row_ref;
    }
    SrbfFitError e;
    e.relative_l2 = ref2 > 0.0 ? std::sqrt(err2 / ref2) : 0.0;
    const glm::dvec3 E_map = envmap_energy(map);
    const glm::dvec3 E_fit = srbf_lights_energy(lights);
    e.energy = (luminance(E_fit) - luminance(E_map)) / luminance(E_map);
    for (int c = 0; c < 3; ++c) e.energy_rgb[c] = E_map[c] > 0.0 ? (E_fit[c] - E_map[c]) / E_map[c] : 0.0;
    return e;
}

EnvMap render_srbf_lights(std::span<const SrbfLight> lights, int width) {
    EnvMap out(width, width / 2);
    for (int row = 0; row < out.height; ++row)
        for (int col = 0; col < out.width; ++col) out.at(col, row) = evaluate_srbf_lights(lights, out.direction(col, row));
    return out;
}

std::vector<SrbfLight> environment_lights(const std::filesystem::path& file, const SrbfFitSettings& settings,
                                          const SrbfFitProgress& progress) {
    if (file.extension() == ".json") return read_srbf_lights(file).lights;
    return fit_srbf_lights(load_envmap(file), settings, progress).lights;
}

}  // namespace coif
