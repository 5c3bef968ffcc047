#include "quadtri/render/integrator/path_integrator.h"

#include <fmt/format.h>

#include "quadtri/math/error.h"
#include "quadtri/render/render_scene.h"
#include "quadtri/render/sampling/frame.h"
#include "quadtri/render/sampling/warp.h"

namespace quadtri {

PathIntegrator::PathIntegrator(const Params& params) : params_(params) {
  if (params.maxDepth < -1 || params.maxDepth == 0)
    fail("path integrator: max_depth {}: expected -1 (no limit) or a positive depth",
         params.maxDepth);
  if (params.rrDepth < 1) fail("path integrator: rr_depth {}: expected at least 1", params.rrDepth);
}

Color PathIntegrator::radianceFrom(const RenderScene& scene, const Ray& cameraRay,
                                   const std::optional<SurfaceInteraction>& first, Pcg32& rng,
                                   uint64_t& rays) const {
  const LightSampler& lights = scene.lightSampler();
  Color result = Color::Zero(), throughput = Color::Ones();
  Ray ray = cameraRay;
  // The previous vertex and how its BSDF sample was drawn, for weighting emission found by it.
  Vec3 previousPoint = ray.origin;
  double previousPdf = 0.0;
  bool previousDelta = true;
  double eta = 1.0;
  std::optional<SurfaceInteraction> traced;  // the hits after the first, which the caller traced
  for (int depth = 0;; ++depth) {
    ++rays;
    if (depth > 0) traced = scene.intersect(ray);
    const std::optional<SurfaceInteraction>& si = depth == 0 ? first : traced;
    const bool countEmission = depth > 0 || !params_.hideEmitters;
    if (!si) {
      const Emitter* env = scene.environment();
      if (env && countEmission) {
        double weight = 1.0;
        if (!previousDelta) {
          const double lightPdf = lights.probability(env) * env->pdfLi(previousPoint, ray.direction,
                                                                       Vec3::Zero(), Vec3::Zero());
          weight = powerHeuristic(1, previousPdf, 1, lightPdf);
        }
        result += throughput * weight * env->eval(Vec3::Zero(), -ray.direction);
      }
      break;
    }
    if (const Emitter* emitter = si->geometry->emitter; emitter && countEmission) {
      const Color emitted = emitter->eval(si->geometricNormal, -ray.direction);
      if (!isBlack(emitted)) {
        double weight = 1.0;
        if (!previousDelta) {
          const double lightPdf =
              lights.probability(emitter) *
              emitter->pdfLi(previousPoint, ray.direction, si->p, si->geometricNormal);
          weight = powerHeuristic(1, previousPdf, 1, lightPdf);
        }
        result += throughput * weight * emitted;
      }
    }
    if (params_.maxDepth >= 0 && depth + 1 >= params_.maxDepth) break;

    const Bsdf& bsdf = *si->geometry->bsdf;
    const Frame frame(si->shadingNormal);
    const Vec3 wi = frame.toLocal(-ray.direction);

    // Next-event estimation: one light chosen by power, one point on it.
    if (!bsdf.isDelta() && !lights.empty()) {
      const LightSampler::Choice choice = lights.choose(rng.nextDouble());
      const Vec2 u = rng.next2D();
      if (const std::optional<LightSample> ls = choice.light->sampleLi(si->p, u)) {
        const Vec3 wo = frame.toLocal(ls->direction);
        const Color f = bsdf.eval(wi, wo);
        if (!isBlack(f)) {
          const Ray shadow = std::isinf(ls->distance)
                                 ? scene.spawnRay(*si, ls->direction)
                                 : scene.spawnRayTo(*si, ls->point, ls->normal, ls->pointError);
          ++rays;
          if (!scene.occluded(shadow)) {
            const double lightPdf = choice.probability * ls->pdf;
            const double weight =
                ls->delta ? 1.0 : powerHeuristic(1, lightPdf, 1, bsdf.pdf(wi, wo));
            result += throughput * f * ls->radiance * (weight / lightPdf);
          }
        }
      }
    }

    // Continue the path by sampling the BSDF.
    const double uLobe = rng.nextDouble();
    const Vec2 u = rng.next2D();
    const std::optional<BsdfSample> bs = bsdf.sample(wi, u, uLobe);
    if (!bs) break;
    throughput *= bs->weight;
    eta *= bs->eta;
    if (isBlack(throughput)) break;
    const Vec3 direction = safeNormalized(frame.toWorld(bs->wo));
    previousPoint = si->p;
    previousPdf = bs->pdf;
    previousDelta = bs->delta;
    ray = scene.spawnRay(*si, direction);

    if (depth + 1 >= params_.rrDepth) {
      // η² undoes the radiance scaling of refraction so glass does not end paths early.
      const double continueProb = std::min(throughput.maxCoeff() * eta * eta, 0.95);
      if (!(rng.nextDouble() < continueProb)) break;
      throughput /= continueProb;
    }
  }
  return result;
}

std::string PathIntegrator::toString() const {
  return fmt::format("path(max_depth={}, rr_depth={}, hide_emitters={})", params_.maxDepth,
                     params_.rrDepth, params_.hideEmitters);
}

}  // namespace quadtri
