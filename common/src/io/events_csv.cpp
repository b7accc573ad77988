#include "kerf/io/events_csv.hpp"

#include "kerf/app/input_error.hpp"

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

namespace kerf {

namespace {

WindowEvent parse_event(const std::string& name, const std::string& file, const std::string& where) {
  if (name == "press") return WindowEvent::press;
  if (name == "move") return WindowEvent::move;
  if (name == "release") return WindowEvent::release;
  if (name == "key_q") return WindowEvent::key_q;
  throw InputError(file, where + ".event", "expected press, move, release or key_q, got \"" + name + "\"");
}

int parse_integer(const std::string& text, const std::string& file, const std::string& where) {
  std::size_t used = 0;
  int value = 0;
  try {
    value = std::stoi(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size()) throw InputError(file, where, "expected an integer, got \"" + text + "\"");
  return value;
}

double parse_seconds(const std::string& text, const std::string& file, const std::string& where) {
  std::size_t used = 0;
  double value = 0.0;
  try {
    value = std::stod(text, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  if (used == 0 || used != text.size() || !std::isfinite(value) || value < 0.0)
    throw InputError(file, where, "expected a time in seconds >= 0, got \"" + text + "\"");
  return value;
}

} // namespace

std::vector<ScriptedEvent> read_events_csv(const std::filesystem::path& path, EventClock clock) {
  const std::string file = path.string();
  const std::string key = clock == EventClock::step ? "step" : "time";
  std::ifstream in(path);
  if (!in) throw InputError(file, "file", "cannot open the events file");
  std::string line;
  const std::string header = key + ",event,x,y,shift";
  if (!std::getline(in, line) || line.rfind(header, 0) != 0) throw InputError(file, "header", "expected the header " + header);
  std::vector<ScriptedEvent> events;
  for (int row = 2; std::getline(in, line); ++row) {
    if (!line.empty() && line.back() == '\r') line.pop_back();
    if (line.empty()) continue;
    std::istringstream fields(line);
    std::string at, event, x, y, shift;
    std::getline(fields, at, ',');
    std::getline(fields, event, ',');
    std::getline(fields, x, ',');
    std::getline(fields, y, ',');
    std::getline(fields, shift);
    const std::string where = "row " + std::to_string(row);
    ScriptedEvent e;
    e.at = clock == EventClock::step ? parse_integer(at, file, where + "." + key) : parse_seconds(at, file, where + "." + key);
    e.event = parse_event(event, file, where);
    e.x = parse_integer(x, file, where + ".x");
    e.y = parse_integer(y, file, where + ".y");
    const int shift_value = parse_integer(shift, file, where + ".shift");
    if (shift_value != 0 && shift_value != 1) throw InputError(file, where + ".shift", "expected 0 or 1");
    e.shift = shift_value == 1;
    if ((clock == EventClock::step && e.at < 1) || (!events.empty() && e.at < events.back().at))
      throw InputError(file, where + "." + key, "expected " + key + "s " + (clock == EventClock::step ? "from 1 on, " : "") + "in increasing order");
    events.push_back(e);
  }
  return events;
}

} // namespace kerf
