// SPDX-License-Identifier: MIT
// shapestruct explore: serves the region-of-interest explorer (dissertation section 4.5) for the output folder of
// `shapestruct fuzzy`, on 127.0.0.1 only: the page (web/explore, bundled at build time) and its JSON API
// (web/explore/API.md). Reads the folder; never writes into it.
#include <atomic>
#include <chrono>
#include <csignal>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <list>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "command.hpp"
#include "option_checks.hpp"
#include "shapestruct/core/errors.hpp"
#include "shapestruct/explore/collection_explorer.hpp"
#include "shapestruct/fuzzy/fuzzy_output.hpp"
#include "shapestruct/io/read_mesh.hpp"
#include "shapestruct/io/segmentation_file.hpp"
#include "shapestruct/templates/part_template.hpp"

// After Eigen: httplib brings in <resolv.h>, whose macro _res would rename a parameter of Eigen's products.
#include <httplib.h>

#ifndef SHAPESTRUCT_EXPLORE_PAGE_DIR
#define SHAPESTRUCT_EXPLORE_PAGE_DIR ""
#endif

namespace {

using namespace shapestruct;
namespace fs = std::filesystem;
using json = nlohmann::json;

/// A 4xx answer: the request was wrong; the message says how.
struct request_error {
  int status;
  std::string message;
};

/// Where the page's files are: --page-dir, the build tree, or the install tree beside the executable.
fs::path find_page_dir(const std::string& option, const char* argv0_dir) {
  if (!option.empty()) {
    if (!fs::is_regular_file(fs::path(option) / "index.html"))
      throw cli::usage_error("--page-dir " + option + " has no index.html");
    return option;
  }
  for (const fs::path& candidate : {fs::path(SHAPESTRUCT_EXPLORE_PAGE_DIR),
                                   fs::path(argv0_dir) / ".." / "share" / "shapestruct" / "explore"})
    if (!candidate.empty() && fs::is_regular_file(candidate / "index.html")) return candidate;
  return {};
}

/// Part labels and template clusters from a `shapestruct templates` output folder, when given.
struct template_output {
  std::vector<std::string> label_names;
  std::map<std::string, int> cluster;  // shape name -> template
  fs::path folder;
};

template_output read_template_output(const std::string& dir) {
  template_output t;
  if (dir.empty()) return t;
  t.folder = dir;
  if (!fs::is_regular_file(t.folder / "templates.json"))
    throw cli::usage_error("--templates " + dir + " is not the output of `shapestruct templates` (templates.json is missing)");
  const auto templates = read_templates((t.folder / "templates.json").string());
  if (!templates.empty())
    for (const auto& part : templates.front().parts) t.label_names.push_back(part.name);
  for (const auto& entry : fs::directory_iterator(t.folder)) {
    const std::string file = entry.path().filename().string();
    const std::string suffix = ".fit.json";
    if (file.size() <= suffix.size() || file.compare(file.size() - suffix.size(), suffix.size(), suffix) != 0) continue;
    std::ifstream in(entry.path());
    const json fit = json::parse(in, nullptr, false);
    if (fit.is_object() && fit.contains("template") && fit["template"].is_number_integer())
      t.cluster[file.substr(0, file.size() - suffix.size())] = fit["template"].get<int>();
  }
  return t;
}

json affine_json(const affine_transform& T) {
  json a = json::array();
  for (int r = 0; r < 3; ++r)
    for (int c = 0; c < 4; ++c) a.push_back(T(r, c));
  return a;
}

template <class Vector>
json floats(const Vector& v) {
  json a = json::array();
  for (index_t i = 0; i < static_cast<index_t>(v.size()); ++i) a.push_back(static_cast<float>(v[i]));
  return a;
}

/// The loaded collection and the answers to every API request.
class explore_service {
 public:
  explore_service(fuzzy_output out, template_output templates, int threads, int page_size)
      : folder_(out.folder), mode_(out.mode), files_(std::move(out.files)), templates_(std::move(templates)),
        page_size_(page_size),
        explorer_(std::move(out.fuzzy), std::move(out.records),
                  collection_explorer_options{.variance = {.threads = threads}, .query = {.threads = threads}}) {}

  const collection_explorer& explorer() const { return explorer_; }

  json collection() const {
    json shapes = json::array();
    for (index_t k = 0; k < explorer_.shapes(); ++k) {
      const shape_record& r = explorer_.records()[std::size_t(k)];
      const auto c = templates_.cluster.find(r.name);
      shapes.push_back({{"index", k},
                        {"name", r.name},
                        {"samples", r.sample_count()},
                        {"vertices", r.vertex_count},
                        {"cluster", c == templates_.cluster.end() ? json(nullptr) : json(c->second)},
                        {"has_labels", !templates_.folder.empty() && fs::exists(templates_.folder / (r.name + ".seg"))}});
    }
    return {{"folder", folder_.string()},
            {"mode", mode_},
            {"shape_count", explorer_.shapes()},
            {"shapes", shapes},
            {"label_names", templates_.label_names},
            {"canonical_reference", explorer_.canonical_reference()},
            {"page_size", page_size_}};
  }

  /// The mesh of shape k as the page draws it (cached: the file is read once).
  std::string mesh(index_t k) {
    check_shape(k);
    {
      std::lock_guard lock(mutex_);
      if (auto it = meshes_.find(k); it != meshes_.end()) return it->second;
    }
    const shape_record& r = explorer_.records()[std::size_t(k)];
    const auto file = read_mesh(files_[std::size_t(k)]);
    const auto& m = file.mesh;
    if (m.V.rows() != r.vertex_count)
      throw request_error{409, "shape '" + r.name + "': " + files_[std::size_t(k)].string() + " has " +
                                   std::to_string(m.V.rows()) + " vertices, the collection's record " +
                                   std::to_string(r.vertex_count) + " (the file changed since `shapestruct fuzzy`)"};
    json labels = nullptr;
    const fs::path seg = templates_.folder.empty() ? fs::path() : templates_.folder / (r.name + ".seg");
    if (!seg.empty() && fs::exists(seg)) {
      const auto polygon_labels = read_segmentation(seg);
      labels = json::array();
      for (std::size_t t = 0; t < file.face_polygon.size(); ++t) {
        const index_t p = file.face_polygon[t];
        labels.push_back(p >= 0 && std::size_t(p) < polygon_labels.size() ? polygon_labels[std::size_t(p)] : -1);
      }
    }
    json faces = json::array();
    for (index_t f = 0; f < m.F.rows(); ++f)
      for (int c = 0; c < 3; ++c) faces.push_back(m.F(f, c));
    json positions = json::array(), samples = json::array();
    for (index_t v = 0; v < m.V.rows(); ++v)
      for (int c = 0; c < 3; ++c) positions.push_back(static_cast<float>(m.V(v, c)));
    for (index_t s = 0; s < r.sample_count(); ++s)
      for (int c = 0; c < 3; ++c) samples.push_back(static_cast<float>(r.samples(s, c)));
    std::string body = json{{"index", k},
                            {"name", r.name},
                            {"positions", positions},
                            {"faces", faces},
                            {"vertex_sample", r.vertex_sample},
                            {"samples", samples},
                            {"face_labels", labels}}
                           .dump();
    std::lock_guard lock(mutex_);
    if (meshes_.size() >= 256) meshes_.clear();  // a bound on memory for large collections; files are re-read
    meshes_.emplace(k, body);
    return body;
  }

  json variance(index_t k) const {
    check_shape(k);
    return {{"index", k}, {"values", floats(explorer_.variance(k))}};
  }

  json canonical() const {
    json transforms = json::array();
    for (const auto& T : explorer_.canonical_transforms()) transforms.push_back(affine_json(T));
    return {{"reference", explorer_.canonical_reference()}, {"transforms", transforms}};
  }

  json query(const json& body) const {
    const auto regions = parse_regions(body);
    const auto t0 = std::chrono::steady_clock::now();
    const collection_ranking ranking = explorer_.sort(regions);
    const double seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    json distance = json::array();
    for (const index_t k : ranking.order) {
      const double d = ranking.distance[std::size_t(k)];
      distance.push_back(std::isfinite(d) ? json(d) : json(nullptr));  // JSON has no infinity: null = no correspondence
    }
    return {{"order", ranking.order}, {"distance", distance}, {"seconds", seconds}};
  }

  json details(const json& body) const {
    const auto regions = parse_regions(body);
    if (!body.contains("shapes") || !body["shapes"].is_array())
      throw request_error{400, "\"shapes\" must be an array of shape indices"};
    std::vector<index_t> shapes;
    for (const auto& s : body["shapes"]) {
      if (!s.is_number_integer()) throw request_error{400, "\"shapes\" must hold integers, got " + s.dump()};
      shapes.push_back(s.get<index_t>());
      check_shape(shapes.back());
    }
    json out = json::array();
    for (const region_match& m : explorer_.details(regions, shapes))
      out.push_back({{"shape", m.shape},
                     {"highlight", floats(m.highlight())},
                     {"transform", affine_json(m.transform)},
                     {"centre", {m.centre.x(), m.centre.y(), m.centre.z()}}});
    return {{"details", out}};
  }

 private:
  void check_shape(index_t k) const {
    if (k < 0 || k >= explorer_.shapes())
      throw request_error{404, "shape " + std::to_string(k) + " is not in the collection (it has " +
                                   std::to_string(explorer_.shapes()) + " shapes, 0.." +
                                   std::to_string(explorer_.shapes() - 1) + ")"};
  }

  /// {"regions": [{"shape": i, "samples": [s, ...]}, ...]} -> regions, each checked (unknown shape or sample:
  /// 404; empty region or a malformed field: 400).
  std::vector<region> parse_regions(const json& body) const {
    if (!body.is_object() || !body.contains("regions") || !body["regions"].is_array())
      throw request_error{400, "the request needs \"regions\": [{\"shape\": i, \"samples\": [s, ...]}, ...]"};
    if (body["regions"].empty()) throw request_error{400, "\"regions\" is empty: paint a region first"};
    std::vector<region> out;
    for (std::size_t n = 0; n < body["regions"].size(); ++n) {
      const json& r = body["regions"][n];
      const std::string which = "region " + std::to_string(n);
      if (!r.is_object() || !r.contains("shape") || !r["shape"].is_number_integer())
        throw request_error{400, which + ": \"shape\" must be a shape index"};
      if (!r.contains("samples") || !r["samples"].is_array())
        throw request_error{400, which + ": \"samples\" must be an array of sample indices"};
      region g{r["shape"].get<index_t>(), {}};
      check_shape(g.shape);
      for (const auto& s : r["samples"]) {
        if (!s.is_number_integer()) throw request_error{400, which + ": sample " + s.dump() + " is not an integer"};
        g.samples.push_back(s.get<index_t>());
      }
      if (g.samples.empty()) throw request_error{400, which + " on shape " + std::to_string(g.shape) + " is empty"};
      const index_t K = explorer_.records()[std::size_t(g.shape)].sample_count();
      for (const index_t s : g.samples)
        if (s < 0 || s >= K)
          throw request_error{404, which + ": sample " + std::to_string(s) + " is not a sample of shape " +
                                       std::to_string(g.shape) + " (it has " + std::to_string(K) + ")"};
      out.push_back(std::move(g));
    }
    return out;
  }

  fs::path folder_;
  std::string mode_;
  std::vector<fs::path> files_;
  template_output templates_;
  int page_size_;
  collection_explorer explorer_;
  std::mutex mutex_;
  std::map<index_t, std::string> meshes_;
};

httplib::Server* running_server = nullptr;
extern "C" void stop_server(int) {
  if (running_server != nullptr) running_server->stop();
}

void answer(httplib::Response& res, const json& body, int status = 200) {
  res.status = status;
  res.set_content(body.dump(), "application/json");
}

/// Runs `handler` and turns what it throws into the right 4xx / 5xx answer, so that no request stops the server.
template <class Handler>
void guarded(httplib::Response& res, Handler&& handler) {
  try {
    handler();
  } catch (const request_error& e) {
    answer(res, {{"error", e.message}}, e.status);
  } catch (const json::exception& e) {
    answer(res, {{"error", std::string("malformed JSON: ") + e.what()}}, 400);
  } catch (const invalid_input& e) {
    answer(res, {{"error", e.what()}}, e.reason() == input_error::empty ? 400 : 404);
  } catch (const io_error& e) {
    answer(res, {{"error", e.what()}}, 500);
  } catch (const std::exception& e) {
    answer(res, {{"error", std::string("internal error: ") + e.what()}}, 500);
  }
}

index_t shape_index(const httplib::Request& req) {
  try {
    return static_cast<index_t>(std::stoll(req.matches[1].str()));
  } catch (const std::exception&) {
    throw request_error{404, "shape '" + req.matches[1].str() + "' is not a shape index"};
  }
}

/// The command line of `shapestruct explore`.
struct explore_options {
  std::string folder;
  long long port = 8765;
  std::string templates_dir;
  long long page_size = 24;
  long long threads = 0;
  std::string page_dir;
};

int run_explore(const explore_options& o) {
  const long long port = o.port;
  const std::string& templates_dir = o.templates_dir;
  const long long page_size = o.page_size;
  const long long threads = o.threads;
  const std::string& page_option = o.page_dir;

  const auto t0 = std::chrono::steady_clock::now();
  const fs::path exe_dir = fs::canonical("/proc/self/exe").parent_path();
  const fs::path page_dir = find_page_dir(page_option, exe_dir.c_str());
  explore_service service(read_fuzzy_output(o.folder), read_template_output(templates_dir), int(threads), int(page_size));
  (void)service.explorer().canonical_reference();  // the first requests should not wait for it
  std::fprintf(stderr, "explore: %ld shapes loaded, canonical view computed in %.2f s\n",
               long(service.explorer().shapes()),
               std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count());

  httplib::Server server;
  // Loopback only, so compression buys nothing, and Debian's httplib brotli-compresses at its slowest setting
  // (seconds for three.js on every page load). Dropping Accept-Encoding before routing serves everything plain;
  // httplib hands the handler the request object it owns and reads the header again after routing.
  server.set_pre_routing_handler([](const httplib::Request& req, httplib::Response&) {
    const_cast<httplib::Request&>(req).headers.erase("Accept-Encoding");
    return httplib::Server::HandlerResponse::Unhandled;
  });
  if (page_dir.empty())
    std::fprintf(stderr, "explore: the page was not built (npm missing at build time?): only the JSON API is served\n");
  else
    server.set_mount_point("/", page_dir.string());
  server.Get("/api/collection", [&](const httplib::Request&, httplib::Response& res) {
    guarded(res, [&] { answer(res, service.collection()); });
  });
  server.Get(R"(/api/shape/([^/]+)/mesh)", [&](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] { res.set_content(service.mesh(shape_index(req)), "application/json"); });
  });
  server.Get(R"(/api/shape/([^/]+)/variance)", [&](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] { answer(res, service.variance(shape_index(req))); });
  });
  server.Get("/api/canonical", [&](const httplib::Request&, httplib::Response& res) {
    guarded(res, [&] { answer(res, service.canonical()); });
  });
  server.Post("/api/query", [&](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] { answer(res, service.query(json::parse(req.body))); });
  });
  server.Post("/api/details", [&](const httplib::Request& req, httplib::Response& res) {
    guarded(res, [&] { answer(res, service.details(json::parse(req.body))); });
  });
  // Unknown paths: a JSON 404 for the API, httplib's own for files.
  server.set_error_handler([](const httplib::Request& req, httplib::Response& res) {
    if (res.status == 404 && req.path.rfind("/api/", 0) == 0 && res.body.empty())
      answer(res, {{"error", "no such API path: " + req.method + " " + req.path + " (see web/explore/API.md)"}}, 404);
  });

  const int bound = port == 0 ? server.bind_to_any_port("127.0.0.1") : (server.bind_to_port("127.0.0.1", int(port)) ? int(port) : -1);
  if (bound < 0)
    throw std::runtime_error("cannot listen on 127.0.0.1:" + std::to_string(port) + " (in use?); choose another with --port");
  running_server = &server;
  std::signal(SIGINT, stop_server);
  std::signal(SIGTERM, stop_server);
  std::printf("explore: serving http://127.0.0.1:%d/\n", bound);
  std::fflush(stdout);
  server.listen_after_bind();
  running_server = nullptr;
  std::fprintf(stderr, "explore: stopped\n");
  return 0;
}

cli::command_fn setup_explore(CLI::App& app) {
  auto o = std::make_shared<explore_options>();
  app.add_option("OUT", o->folder, "the output folder of `shapestruct fuzzy`")->required();
  app.add_option("--port", o->port, "port (default 8765; 0 picks a free one); the line 'explore: serving URL'\nsays which")
      ->type_name("P")
      ->check(cli::in_range(0LL, 65535LL));
  app.add_option("--templates", o->templates_dir,
                 "output of `shapestruct templates` on the same shapes: part labels and\ntemplate clusters")
      ->type_name("DIR");
  app.add_option("--page-size", o->page_size, "shapes per results page (default 24)")->type_name("N")->check(cli::at_least(1LL));
  app.add_option("--threads", o->threads, "threads for queries (default 0 = all cores)")->type_name("N")->check(cli::at_least(0LL));
  app.add_option("--page-dir", o->page_dir,
                 "the page's files (default: the folder bundled at build time, or\nshare/shapestruct/explore beside the "
                 "installed tool)")
      ->type_name("DIR");
  app.footer(
      "Serves the collection explorer for OUT, the output folder of `shapestruct fuzzy`, at http://127.0.0.1:P/\n"
      "(loopback only): paint a region of interest on example shapes, sort the collection by similarity to it,\n"
      "see where the collection varies, align every shape to a canonical view or to the region (docs/explore.md).\n"
      "Nothing is written into OUT.");
  return [o] { return run_explore(*o); };
}

const cli::register_command reg_explore{"explore", {"serve the region-of-interest explorer of a fuzzy collection", setup_explore}};

}  // namespace
