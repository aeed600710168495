#include "shadetlm/trace/timeline.hpp"

#include <algorithm>
#include <cctype>
#include <charconv>
#include <numeric>
#include <stdexcept>
#include <tuple>

#include <nlohmann/json.hpp>

#include "shadetlm/core/output.hpp"
#include "shadetlm/core/version.hpp"

namespace shadetlm::modules {

extern const char* const kTimelineViewer;  // timeline_viewer.html, built in (CMakeLists.txt)

namespace {

// The JSON's text, appended to a string: numbers through to_chars (150 000 slices).
struct Json {
  std::string& out;
  Json& operator<<(std::string_view s) {
    out += s;
    return *this;
  }
  Json& operator<<(uint64_t n) {
    char b[24];
    out.append(b, size_t(std::to_chars(b, b + sizeof b, n).ptr - b));
    return *this;
  }
  Json& operator<<(double v) {  // shortest text that reads back as v
    char b[32];
    out.append(b, size_t(std::to_chars(b, b + sizeof b, v).ptr - b));
    return *this;
  }
};

std::string quoted(const std::string& text) {  // a JSON string, whatever the bytes
  return nlohmann::json(text).dump(-1, ' ', false, nlohmann::json::error_handler_t::replace);
}

// What a slice carries, as its name: "tri 12 · y 34 · x 10 · 8 px", setup's "tri 12".
std::string slice_name(const Timeline::Slice& s) {
  std::string name = "tri " + std::to_string(s.triangle);
  if (s.y >= 0)
    name += " \u00b7 y " + std::to_string(s.y) + " \u00b7 x " + std::to_string(s.x) + " \u00b7 " +
            std::to_string(s.pixels) + " px";
  return name;
}

}  // namespace

// Each slice's length as drawn: a block overlaps packets (the next one starts while
// the last pixels of this one are in flight or stalled), and a track's slices must not
// overlap, so a slice is drawn up to the next one's start; its args keep the true span.
std::vector<uint64_t> Timeline::shown_cycles() const {
  std::vector<uint32_t> order(slices_.size());
  std::iota(order.begin(), order.end(), 0);
  std::stable_sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) {
    return std::tie(slices_[a].block, slices_[a].start) < std::tie(slices_[b].block, slices_[b].start);
  });
  std::vector<uint64_t> shown(slices_.size());
  for (size_t k = 0; k < order.size(); ++k) {
    const Slice& s = slices_[order[k]];
    shown[order[k]] = s.busy;
    if (k + 1 < order.size() && slices_[order[k + 1]].block == s.block)
      shown[order[k]] = std::min(s.busy, slices_[order[k + 1]].start - s.start);
  }
  return shown;
}

void Timeline::add_series(const std::string& name, const std::string& unit, uint64_t bin,
                          const std::vector<uint64_t>& totals, uint64_t end, double scale) {
  Series s{name, unit, bin, end, {}};
  for (size_t k = 0; k < totals.size() && k * bin < end; ++k) {
    const uint64_t length = std::min(bin, end - k * bin);  // the last bin's part
    s.per_bin.push_back(double(totals[k]) / double(length) * scale);
  }
  series_.push_back(std::move(s));
}

// The packets: their slices (indices) in pipeline order, a packet being its triangle,
// row and first pixel; numbered in that order (the `packet` argument and flow id).
std::vector<std::vector<uint32_t>> Timeline::packets() const {
  std::vector<uint32_t> order;
  for (uint32_t k = 0; k < slices_.size(); ++k)
    if (slices_[k].y >= 0) order.push_back(k);
  auto key = [&](uint32_t k) {
    const Slice& s = slices_[k];
    return std::tuple(s.triangle, s.y, s.x, s.block, s.start);
  };
  std::sort(order.begin(), order.end(), [&](uint32_t a, uint32_t b) { return key(a) < key(b); });
  std::vector<std::vector<uint32_t>> packets;
  for (size_t k = 0; k < order.size(); ++k) {
    const Slice& s = slices_[order[k]];
    if (k == 0 || std::tie(s.triangle, s.y, s.x) != std::tie(slices_[order[k - 1]].triangle, slices_[order[k - 1]].y,
                                                              slices_[order[k - 1]].x))
      packets.emplace_back();
    packets.back().push_back(order[k]);
  }
  return packets;
}

// One chain of flow events a packet, through its slices in pipeline order: "s" in the
// first, "t" in those between, "f" in the last, each at its slice's start (inside it).
void Timeline::write_flows(std::string& text, const std::vector<std::vector<uint32_t>>& packets) const {
  Json out{text};
  for (uint64_t id = 0; id < packets.size(); ++id) {
    const std::vector<uint32_t>& chain = packets[id];
    for (size_t k = 0; chain.size() > 1 && k < chain.size(); ++k) {
      const Slice& s = slices_[chain[k]];
      const bool first = k == 0, last = k + 1 == chain.size();
      out << ",\n{\"ph\": \"" << (first ? "s" : last ? "f" : "t") << "\"" << (last ? ", \"bp\": \"e\"" : "")
          << ", \"pid\": 1, \"tid\": " << uint64_t(s.block) << ", \"cat\": \"packet\", \"name\": \"packet\", \"id\": " << id
          << ", \"ts\": " << s.start << "}";
    }
  }
}

void Timeline::add_fifo_series(const std::vector<std::string>& names, const std::vector<uint64_t>& depths,
                               uint64_t end) {
  frame_cycles_ = end;
  for (size_t b = 0; b < waited_.size(); ++b)
    if (!waited_[b].empty()) {
      add_series(names[b] + " FIFO", "pixels", fifo_bin_, waited_[b], end, 1);
      series_.back().full = double(depths[b]);
    }
}

std::string Timeline::json(const std::vector<std::string>& names, double clock_mhz, const std::string& scene) const {
  std::string text;
  Json out{text};
  out << "{\"otherData\": {\"time_unit\": \"cycles\", \"clock_mhz\": " << clock_mhz
      << ", \"version\": " << quoted(core::kVersion) << ", \"scene\": " << quoted(scene)
      // For the viewer: the frame's cycles beside the trace's (a region's ends sooner),
      // and the value that fills a counter's track (a FIFO's depth).
      << ", \"frame_cycles\": " << frame_cycles_ << ", \"region\": " << (region_ ? "true" : "false") << ", \"counter_full\": {";
  bool first = true;
  for (const auto& s : series_)
    if (s.full > 0) out << (first ? "" : ", ") << quoted(s.name) << ": " << s.full, first = false;
  out << "}},\n\"traceEvents\": [\n"
      << "{\"ph\": \"M\", \"pid\": 1, \"name\": \"process_name\", \"args\": {\"name\": \"shadetlm pipeline\"}}";
  for (size_t b = 0; b < names.size(); ++b)  // the tracks, in pipeline order
    out << ",\n{\"ph\": \"M\", \"pid\": 1, \"tid\": " << uint64_t(b) << ", \"name\": \"thread_name\", \"args\": {\"name\": "
        << quoted(names[b]) << "}},\n{\"ph\": \"M\", \"pid\": 1, \"tid\": " << uint64_t(b)
        << ", \"name\": \"thread_sort_index\", \"args\": {\"sort_index\": " << uint64_t(b) << "}}";
  uint64_t from = UINT64_MAX, to = 0;  // the slices' span
  const std::vector<uint64_t> shown = shown_cycles();
  const std::vector<std::vector<uint32_t>> chains = packets();
  std::vector<int64_t> packet_of(slices_.size(), -1);
  for (size_t id = 0; id < chains.size(); ++id)
    for (uint32_t k : chains[id]) packet_of[k] = int64_t(id);
  for (size_t k = 0; k < slices_.size(); ++k) {
    const Slice& s = slices_[k];
    from = std::min(from, s.start), to = std::max(to, s.start + s.busy);
    out << ",\n{\"ph\": \"X\", \"pid\": 1, \"tid\": " << uint64_t(s.block) << ", \"name\": \"" << slice_name(s)
        << "\", \"ts\": " << s.start << ", \"dur\": " << shown[k] << ", \"args\": {\"triangle\": " << uint64_t(s.triangle);
    if (s.y >= 0)
      out << ", \"packet\": " << uint64_t(packet_of[k]) << ", \"y\": " << uint64_t(s.y) << ", \"x\": " << uint64_t(s.x)
          << ", \"pixels\": " << uint64_t(s.pixels) << ", \"stalled_cycles\": " << s.stalled
          << ", \"stalled_pixel_cycles\": " << s.stalled_pixels;
    out << ", \"cycles\": " << s.busy << "}}";
  }
  write_flows(text, chains);
  for (const auto& s : series_)
    for (size_t k = 0; k < s.per_bin.size(); ++k) {
      const uint64_t start = k * s.bin;
      if (region_ && (start + s.bin <= from || start >= to)) continue;
      out << ",\n{\"ph\": \"C\", \"pid\": 1, \"name\": " << quoted(s.name) << ", \"ts\": " << start << ", \"args\": {\""
          << s.unit << "\": " << s.per_bin[k] << ", \"cycles\": " << std::min(s.bin, s.end - start) << "}}";
    }
  out << "\n]}\n";
  return text;
}

std::string timeline_page(const std::string& json) {
  // Inside <script>, "</script" or "<!--" in a string (a scene's path) would end or
  // change the element: every < becomes \u003c, the same JSON string.
  std::string escaped;
  escaped.reserve(json.size());
  for (char c : json) escaped += c == '<' ? std::string_view("\\u003c") : std::string_view(&c, 1);
  const std::string page = kTimelineViewer, mark = "/*SHADETLM_TRACE_JSON*/";
  const size_t at = page.find(mark);
  if (at == std::string::npos) throw std::logic_error("the timeline viewer has no place for the trace");
  return page.substr(0, at) + escaped + page.substr(at + mark.size());
}

void Timeline::write(core::OutputSet& outputs, const std::string& path, const std::vector<std::string>& names, double clock_mhz,
                     const std::string& scene) const {
  std::string end = path.size() >= 5 ? path.substr(path.size() - 5) : "";
  for (char& c : end) c = char(std::tolower(static_cast<unsigned char>(c)));
  const bool html = end == ".html";  // (any case, as the render's check takes it)
  const std::string text = json(names, clock_mhz, scene);
  outputs.write(path, html ? timeline_page(text) : text);
}

}  // namespace shadetlm::modules
