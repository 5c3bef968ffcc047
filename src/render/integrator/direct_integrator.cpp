#include "quadtri/render/integrator/direct_integrator.h"

#include <fmt/format.h>

#include "quadtri/math/error.h"
#include "quadtri/render/render_scene.h"
#include "quadtri/render/sampling/frame.h"
#include "quadtri/render/sampling/warp.h"

namespace quadtri {

DirectIntegrator::DirectIntegrator(const Params& params) : params_(params) {
  if (params.emitterSamples < 0 || params.bsdfSamples < 0 ||
      params.emitterSamples + params.bsdfSamples == 0)
    fail(
        "direct integrator: emitter_samples {} and bsdf_samples {}: expected non-negative counts, "
        "not both 0",
        params.emitterSamples, params.bsdfSamples);
}

Color DirectIntegrator::radianceFrom(const RenderScene& scene, const Ray& ray,
                                     const std::optional<SurfaceInteraction>& si, Pcg32& rng,
                                     uint64_t& rays) const {
  const LightSampler& lights = scene.lightSampler();
  ++rays;
  if (!si) {
    const Emitter* env = scene.environment();
    return env && !params_.hideEmitters ? env->eval(Vec3::Zero(), -ray.direction) : Color::Zero();
  }
  Color result = Color::Zero();
  if (si->geometry->emitter && !params_.hideEmitters)
    result += si->geometry->emitter->eval(si->geometricNormal, -ray.direction);

  const Bsdf& bsdf = *si->geometry->bsdf;
  const Frame frame(si->shadingNormal);
  const Vec3 wi = frame.toLocal(-ray.direction);
  const bool delta = bsdf.isDelta();
  const int ne = delta ? 0 : params_.emitterSamples;
  const int nb = delta ? std::max(params_.bsdfSamples, 1) : params_.bsdfSamples;

  for (int i = 0; i < ne && !lights.empty(); ++i) {
    const LightSampler::Choice choice = lights.choose(rng.nextDouble());
    const std::optional<LightSample> ls = choice.light->sampleLi(si->p, rng.next2D());
    if (!ls) continue;
    const Vec3 wo = frame.toLocal(ls->direction);
    const Color f = bsdf.eval(wi, wo);
    if (isBlack(f)) continue;
    ++rays;
    const Ray shadow = std::isinf(ls->distance)
                           ? scene.spawnRay(*si, ls->direction)
                           : scene.spawnRayTo(*si, ls->point, ls->normal, ls->pointError);
    if (scene.occluded(shadow)) continue;
    const double lightPdf = choice.probability * ls->pdf;
    const double weight = ls->delta ? 1.0 : powerHeuristic(ne, lightPdf, nb, bsdf.pdf(wi, wo));
    result += f * ls->radiance * (weight / (lightPdf * ne));
  }

  for (int i = 0; i < nb; ++i) {
    const double uLobe = rng.nextDouble();
    const std::optional<BsdfSample> bs = bsdf.sample(wi, rng.next2D(), uLobe);
    if (!bs) continue;
    const Vec3 direction = safeNormalized(frame.toWorld(bs->wo));
    ++rays;
    const std::optional<SurfaceInteraction> hit = scene.intersect(scene.spawnRay(*si, direction));
    const Emitter* emitter = hit ? hit->geometry->emitter : scene.environment();
    if (!emitter) continue;
    const Color emitted = hit ? emitter->eval(hit->geometricNormal, -direction)
                              : emitter->eval(Vec3::Zero(), -direction);
    if (isBlack(emitted)) continue;
    double weight = 1.0;
    if (!bs->delta && ne > 0) {
      const double lightPdf = lights.probability(emitter) *
                              (hit ? emitter->pdfLi(si->p, direction, hit->p, hit->geometricNormal)
                                   : emitter->pdfLi(si->p, direction, Vec3::Zero(), Vec3::Zero()));
      weight = powerHeuristic(nb, bs->pdf, ne, lightPdf);
    }
    result += bs->weight * emitted * (weight / nb);
  }
  return result;
}

std::string DirectIntegrator::toString() const {
  return fmt::format("direct(emitter_samples={}, bsdf_samples={}, hide_emitters={})",
                     params_.emitterSamples, params_.bsdfSamples, params_.hideEmitters);
}

}  // namespace quadtri
