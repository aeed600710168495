// Inspection (docs/inspecting.md): the VCD is well formed and says what the frame
// says, the GTKWave view names only signals of the VCD, the timeline has one slice
// per packet. Each test case runs one simulation (one per process).
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <random>
#include <set>

#include <nlohmann/json.hpp>

#include "shadetlm/modules/normalize/normalize_kernel.hpp"
#include "shadetlm/modules/pipeline/pipeline.hpp"
#include "systemc_harness.hpp"
#include "test_util.hpp"
#include "vcd_reader.hpp"

using namespace shadetlm;  // core::, modules::, reference::

TEST_CASE("the VCD is well formed and its traced values are the frame's", "[inspect][systemc]") {
  test::route_systemc_reports_to_failures();
  const auto dir = test::temp_dir("vcd");
  const core::Scene scene = core::load_scene(test::source_path("golden/point-light/scene.json"));
  modules::Inspect inspect;
  inspect.vcd = (dir / "trace.vcd").string();
  inspect.region = {40, 30, 71, 45};  // on the sphere and the floor
  inspect.region_given = true;
  const modules::RenderResult r = modules::render_systemc(scene, inspect);
  REQUIRE(r.trace_records > 0);

  const test::Vcd vcd = test::read_vcd(inspect.vcd);
  CHECK(vcd.header_ok);
  CHECK(vcd.times_ok);
  // Replay the framebuffer's signals: at each rise of valid, the pixel written.
  const std::string fb = "shadetlm.framebuffer.";
  for (const char* s : {"valid", "x[31:0]", "y[31:0]", "r", "g", "b", "z"}) REQUIRE(vcd.id_of.count(fb + s));
  std::map<std::string, double> value;
  std::map<std::pair<int, int>, std::array<double, 4>> written;  // last write per pixel
  uint64_t time = ~0ull;
  auto flush = [&]() {
    if (value[fb + "valid"] != 1) return;
    written[{int(value[fb + "x[31:0]"]), int(value[fb + "y[31:0]"])}] = {value[fb + "r"], value[fb + "g"],
                                                                         value[fb + "b"], value[fb + "z"]};
  };
  for (const auto& c : vcd.changes) {
    if (c.time != time) flush(), time = c.time;
    value[vcd.name_of.at(c.id)] = c.value;
  }
  flush();
  // While not valid, the integers are x (triangle 0 and pixel 0, 0 exist).
  uint64_t unknown = 0;
  for (const auto& c : vcd.changes) unknown += vcd.name_of.at(c.id) == fb + "x[31:0]" && std::isnan(c.value);
  CHECK(unknown > 0);
  int checked = 0;
  for (const auto& [xy, v] : written) {
    const size_t i = size_t(xy.second) * r.frame.width + xy.first;
    INFO("pixel " << xy.first << ", " << xy.second);
    CHECK(inspect.region.contains(xy.first, xy.second));
    CHECK(v[0] == Approx(r.frame.at("R")[i]).epsilon(1e-6));
    CHECK(v[1] == Approx(r.frame.at("G")[i]).epsilon(1e-6));
    CHECK(v[2] == Approx(r.frame.at("B")[i]).epsilon(1e-6));
    CHECK(v[3] == Approx(r.frame.at("Z")[i]).epsilon(1e-6));
    ++checked;
  }
  // Every covered pixel of the region was written, and was seen written.
  int covered = 0;
  for (int y = inspect.region.y0; y <= inspect.region.y1; ++y)
    for (int x = inspect.region.x0; x <= inspect.region.x1; ++x)
      covered += r.frame.at("A")[size_t(y) * r.frame.width + x] > 0;
  CHECK(checked == covered);
  CHECK(checked > 100);

  // The GTKWave view names only signals that exist, and names every block's valid.
  std::ifstream gtkw((dir / "trace.gtkw").string());
  REQUIRE(gtkw);
  std::string line;
  int named = 0;
  std::set<std::string> blocks;
  while (std::getline(gtkw, line)) {
    if (line.empty() || line[0] == '@' || line[0] == '-' || line[0] == '[' || line[0] == '*') continue;
    INFO(line);
    CHECK(vcd.id_of.count(line) == 1);
    if (line.size() > 6 && line.substr(line.size() - 6) == ".valid") blocks.insert(line);
    ++named;
  }
  CHECK(named > 30);
  // The view names its dump by a path relative to itself (the pair can be moved).
  std::ifstream view((dir / "trace.gtkw").string());
  const std::string text((std::istreambuf_iterator<char>(view)), std::istreambuf_iterator<char>());
  CHECK(text.find("[dumpfile] \"trace.vcd\"") != std::string::npos);
  CHECK(blocks.size() == r.blocks.size() - 1);  // every block but setup has a probe
}

TEST_CASE("the timeline: a slice per packet, named by what it carries, flows across the blocks, counters",
          "[inspect][systemc]") {
  test::route_systemc_reports_to_failures();
  const auto dir = test::temp_dir("timeline");
  const core::Scene scene = core::load_scene(test::source_path("golden/demo/scene.json"));
  modules::Inspect inspect;
  inspect.timeline = (dir / "timeline.json").string();
  const modules::RenderResult r = modules::render_systemc(scene, inspect);
  std::ifstream in(inspect.timeline);
  const nlohmann::json j = nlohmann::json::parse(in);  // throws if not valid JSON
  CHECK(j.at("otherData").at("time_unit") == "cycles");
  std::map<int, std::string> track;
  std::map<int, uint64_t> slices, slice_end;
  std::map<std::string, uint64_t> counters;  // samples per counter
  std::map<uint64_t, std::vector<int>> flows;  // per flow id, its tracks in order
  std::map<uint64_t, std::set<int>> packet_tracks;  // per slice's packet argument, its tracks
  std::map<std::string, double> waited;  // per FIFO counter: Σ mean occupancy × bin cycles
  for (const auto& e : j.at("traceEvents")) {
    if (e.at("ph") == "M" && e.at("name") == "thread_name") track[e.at("tid")] = e.at("args").at("name");
    if (e.contains("ts")) CHECK(e.at("ts").is_number_unsigned());  // integer cycles
    if (e.at("ph") == "C") {
      ++counters[e.at("name")];
      const nlohmann::json& v = e.at("args");
      if (v.contains("pixels")) CHECK(v.at("pixels").get<double>() <= 8);  // the default FIFO depth
      if (v.contains("percent")) CHECK(v.at("percent").get<double>() <= 100);
      if (v.contains("pixels")) waited[e.at("name")] += v.at("pixels").get<double>() * v.at("cycles").get<double>();
    }
    if (e.at("ph") == "X") {
      const int tid = e.at("tid");
      ++slices[tid];
      const uint64_t ts = e.at("ts"), dur = e.at("dur");
      CHECK(ts >= slice_end[tid]);  // a track's slices never overlap
      slice_end[tid] = ts + dur;
      const nlohmann::json& a = e.at("args");
      const std::string name = e.at("name");
      CHECK(name.rfind("tri " + std::to_string(a.at("triangle").get<uint32_t>()), 0) == 0);
      if (tid >= 1) {
        CHECK(name.find(std::to_string(a.at("pixels").get<int>()) + " px") != std::string::npos);
        packet_tracks[a.at("packet")].insert(tid);
      }
    }
    if (e.at("ph") == "s" || e.at("ph") == "t" || e.at("ph") == "f") flows[e.at("id")].push_back(e.at("tid"));
  }
  REQUIRE(track.size() == r.blocks.size());
  for (size_t b = 0; b < r.blocks.size(); ++b) {
    INFO(r.blocks[b].name);
    CHECK(track[int(b)] == r.blocks[b].name);
    // setup: one slice per triangle; the raster and the span blocks: one per packet.
    const uint64_t expected = b < 1 ? r.triangles_drawn : r.blocks[b].stats.packets;
    CHECK(slices[int(b)] == expected);
    CHECK(counters[r.blocks[b].name + " utilization"] > 0);
    if (b >= 2) {  // the FIFO counter holds every cycle a pixel waited in it, as the stats count them
      CHECK(counters[r.blocks[b].name + " FIFO"] > 0);
      CHECK(waited[r.blocks[b].name + " FIFO"] == Approx(double(r.blocks[b].stats.fifo_cycles)).epsilon(1e-9));
    }
  }
  // One flow a packet, from the raster through every span block, in pipeline order.
  CHECK(flows.size() == r.blocks[1].stats.packets);
  for (const auto& [id, tracks] : flows) {
    CHECK(tracks.front() == 1);
    CHECK(std::is_sorted(tracks.begin(), tracks.end()));
    // The slices' packet argument names the same packet as the flow's id.
    CHECK(std::set<int>(tracks.begin(), tracks.end()) == packet_tracks[id]);
  }
}

TEST_CASE("the timeline of a traced region keeps its triangles and packets on every track", "[inspect][systemc]") {
  test::route_systemc_reports_to_failures();
  const auto dir = test::temp_dir("timeline-region");
  const core::Scene scene = core::load_scene(test::source_path("golden/demo/scene.json"));
  modules::Inspect inspect;
  inspect.timeline = (dir / "region.html").string();
  inspect.region = {40, 20, 59, 35};
  inspect.region_given = true;
  const modules::RenderResult r = modules::render_systemc(scene, inspect);
  std::ifstream in(inspect.timeline);
  const std::string page((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
  // The page holds the trace: the JSON between its script element's tags.
  const std::string open = "<script id=\"trace-data\" type=\"application/json\">";
  const size_t from = page.find(open);
  REQUIRE(from != std::string::npos);
  const size_t to = page.find("</script>", from);
  const nlohmann::json j = nlohmann::json::parse(page.substr(from + open.size(), to - from - open.size()));
  std::set<uint32_t> setup, rastered;  // triangles with a slice on setup's track, on the raster's
  uint64_t packets = 0;
  for (const auto& e : j.at("traceEvents")) {
    if (e.at("ph") != "X") continue;
    const nlohmann::json& a = e.at("args");
    if (e.at("tid") == 0) {
      setup.insert(a.at("triangle").get<uint32_t>());
      continue;
    }
    if (e.at("tid") == 1) rastered.insert(a.at("triangle").get<uint32_t>());
    ++packets;
    INFO(e.dump());
    CHECK(a.at("y").get<int>() >= 20);
    CHECK(a.at("y").get<int>() <= 35);
    CHECK(a.at("x").get<int>() <= 59);
    CHECK(a.at("x").get<int>() + a.at("pixels").get<int>() > 40);
  }
  CHECK(packets > 0);
  // Setup keeps the triangles whose bounds reach the region: those with packets there
  // and few more (the region is 3.5 % of the frame).
  CHECK(std::includes(setup.begin(), setup.end(), rastered.begin(), rastered.end()));
  CHECK(setup.size() < rastered.size() * 11 / 10);
  CHECK(setup.size() < r.triangles_drawn / 4);
}

TEST_CASE("every traced record reaches the VCD, also when the replay idles", "[inspect][systemc]") {
  // At 128×72 setup is the bottleneck and traced triangles come in bursts with idle
  // stretches between them: the replay thread must wake for records after idling, and
  // the last time step must reach the file.
  test::route_systemc_reports_to_failures();
  const auto dir = test::temp_dir("vcd-idle");
  const core::Scene scene = core::load_scene(test::source_path("golden/demo/scene.json"));
  modules::Inspect inspect;
  inspect.vcd = (dir / "idle.vcd").string();
  inspect.region = {0, 0, 127, 71, 1300, 1400};
  inspect.region_given = true;
  inspect.timeline = (dir / "idle.json").string();
  const modules::RenderResult r = modules::render_systemc(scene, inspect);
  REQUIRE(r.trace_records > 100);
  const test::Vcd vcd = test::read_vcd(inspect.vcd);
  REQUIRE(vcd.header_ok);
  // A record is a cycle at which a block's valid is high with a new pixel: count the
  // time steps where some block's x, y or triangle changes, or its valid rises, while
  // its valid is (then) high.
  std::map<std::string, double> value;
  std::set<std::string> blocks;
  for (const auto& [id, name] : vcd.name_of)
    if (name.size() > 6 && name.substr(name.size() - 6) == ".valid") blocks.insert(name.substr(0, name.size() - 5));
  uint64_t seen = 0, time = ~0ull;
  std::set<std::string> touched;
  auto flush = [&]() {
    for (const auto& b : touched)
      if (value[b + "valid"] == 1) ++seen;
    touched.clear();
  };
  bool ended = false;
  for (const auto& c : vcd.changes) {
    if (c.time != time) flush(), time = c.time;
    const std::string& name = vcd.name_of.at(c.id);
    value[name] = c.value;
    const auto dot = name.rfind('.');
    const std::string block = name.substr(0, dot + 1), signal = name.substr(dot + 1);
    if (blocks.count(block) && (signal == "valid" || signal == "x[31:0]" || signal == "y[31:0]" || signal == "triangle[31:0]"))
      touched.insert(block);
    if (name == "shadetlm.end_of_trace" && c.value == 1) ended = true;
  }
  flush();
  CHECK(seen == r.trace_records);
  CHECK(ended);  // the marker past the last record is in the file
  // The timeline keeps the same triangles only.
  std::ifstream in(inspect.timeline);
  const nlohmann::json j = nlohmann::json::parse(in);
  for (const auto& e : j.at("traceEvents"))
    if (e.at("ph") == "X") {
      CHECK(e.at("args").at("triangle").get<uint32_t>() >= 1300);
      CHECK(e.at("args").at("triangle").get<uint32_t>() <= 1400);
    }
}

