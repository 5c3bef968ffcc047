// render(): a scene file rendered as `quadtri render` renders it, to a float32 array.
#include <pybind11/stl.h>

#include <atomic>
#include <chrono>
#include <future>

#include "arrays.h"
#include "bindings.h"
#include "quadtri/math/error.h"
#include "quadtri/scene/scene_render.h"

namespace quadtri::python {

namespace {

// A define's value as the scene file would spell it: str as is, bools as true/false, numbers
// as Python prints them.
std::string defineValue(const std::string& name, py::handle value) {
  if (py::isinstance<py::bool_>(value)) return value.cast<bool>() ? "true" : "false";
  if (py::isinstance<py::str>(value)) return value.cast<std::string>();
  if (py::isinstance<py::int_>(value) || py::isinstance<py::float_>(value)) return py::str(value);
  throw py::type_error(fmt::format("defines['{}']: expected a str, int, float or bool, got a {}",
                                   name,
                                   std::string(py::str(py::type::of(value).attr("__name__")))));
}

}  // namespace

void bindRender(py::module_& m) {
  m.def(
      "render",
      [](py::handle scene, std::optional<int> spp, std::optional<py::dict> defines,
         std::optional<std::string> model, py::handle seedArg, int threads,
         std::optional<double> time, bool returnStats) {
        const std::string file = pathOf(scene);
        SceneRenderRequest request;
        RenderSettings& settings = request.settings;
        if (defines)
          for (const auto& [key, value] : *defines) {
            const std::string name = py::str(key);
            settings.defines[name] = defineValue(name, value);
          }
        settings.model = model;
        settings.samplesPerPixel = spp;
        if (!seedArg.is_none()) settings.seed = wholeNumber(seedArg, "seed");
        settings.threads = threads;
        if (time && !(*time > 0.0))
          throw py::value_error(
              fmt::format("time {}: expected a positive number of seconds", *time));
        settings.timeLimitSeconds = time.value_or(0.0);
        std::vector<std::string> warnings;
        request.warn = [&warnings](const std::string& w) { warnings.push_back(w); };

        // The render runs on a thread of its own while this one, holding the GIL now and then,
        // looks for Ctrl-C: it cancels the render as the CLI's SIGINT handler does, and raises.
        std::atomic<bool> cancel{false};
        auto work = [&]() {
          PreparedRender prepared = prepareSceneRender(file, request);
          prepared.options.cancel = &cancel;
          RenderResult result =
              render(*prepared.built.scene, *prepared.built.integrator, prepared.options);
          return std::pair{std::move(prepared), std::move(result)};
        };
        std::future<std::pair<PreparedRender, RenderResult>> pending;
        {
          py::gil_scoped_release release;
          pending = std::async(std::launch::async, work);
        }
        while (true) {
          std::future_status status;
          {
            py::gil_scoped_release release;
            status = pending.wait_for(std::chrono::milliseconds(50));
          }
          if (status == std::future_status::ready) break;
          if (PyErr_CheckSignals() != 0) {  // KeyboardInterrupt (or a handler's exception)
            cancel.store(true);
            {
              py::gil_scoped_release release;
              pending.wait();
            }
            throw py::error_already_set();
          }
        }
        std::pair<PreparedRender, RenderResult> done = [&] {
          py::gil_scoped_release release;
          return pending.get();  // rethrows the render's Error
        }();
        for (const std::string& w : warnings) warn(PyExc_UserWarning, w);
        const PreparedRender& prepared = done.first;
        const RenderResult& result = done.second;
        const RenderStats& s = result.stats;
        if (s.nonFiniteSamples)
          warn(PyExc_UserWarning, fmt::format("{} NaN/Inf samples dropped", s.nonFiniteSamples));
        if (s.unfinishedPixels)
          warn(PyExc_UserWarning,
               fmt::format("{} of {} pixels not rendered (time limit), left black",
                           s.unfinishedPixels, result.image.pixels.size()));

        const Image& image = result.image;
        py::array_t<float> out(
            {py::ssize_t(image.height), py::ssize_t(image.width), py::ssize_t(3)});
        float* p = out.mutable_data();
        for (size_t i = 0; i < image.pixels.size(); ++i)
          for (int c = 0; c < 3; ++c) p[3 * i + c] = float(image.pixels[i][c]);
        if (!returnStats) return py::object(out);
        py::dict stats;
        stats["integrator"] = prepared.built.integrator->toString();
        stats["width"] = image.width;
        stats["height"] = image.height;
        stats["samples_per_pixel"] = s.meanSamplesPerPixel();
        stats["seconds"] = s.seconds;
        stats["first_pixel_seconds"] = s.firstPixelSeconds;
        stats["samples"] = s.samples;
        stats["rays"] = s.rays;
        stats["finished_pixels"] = s.finishedPixels;
        stats["unfinished_pixels"] = s.unfinishedPixels;
        stats["non_finite_samples"] = s.nonFiniteSamples;
        stats["primitives"] = prepared.built.scene->primitiveCount();
        stats["input_triangles"] = prepared.built.inputTriangles;
        stats["geometry_bytes"] = prepared.built.scene->geometryBytes();
        return py::object(py::make_tuple(out, stats));
      },
      py::arg("scene"), py::arg("spp") = py::none(), py::arg("defines") = py::none(),
      py::arg("model") = py::none(), py::arg("seed") = py::none(), py::arg("threads") = 0,
      py::arg("time") = py::none(), py::arg("return_stats") = false, R"doc(
Renders a Mitsuba 3 XML scene file as `quadtri render SCENE` does (the same library calls, so the
same image as its .exr for the same arguments) and returns its linear radiance as a float32 array
(height, width, 3), row 0 at the top.

spp: samples per pixel (--spp: overrides the sampler, caps an adaptive integrator); defines:
{name: value} (-D name=value, values str, int, float or bool); model: the model of every obj/ply
shape (--model); seed (--seed); threads (--threads, 0: all; the image does not depend on it);
time: a budget in seconds (--time), pixels not started in time stay black. A define the file
has no <default> for, dropped NaN samples and unrendered pixels give a UserWarning with the
CLI's text. Ctrl-C stops the render and raises KeyboardInterrupt. With return_stats=True returns
(image, stats), stats a dict of the CLI's summary: integrator, samples_per_pixel, seconds,
first_pixel_seconds (from the render's start), samples, rays, primitives, input_triangles,
geometry_bytes, ...
)doc");
}

}  // namespace quadtri::python
