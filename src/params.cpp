#include "params.h"

#include <cctype>
#include <cmath>
#include <sstream>

namespace multirobot_audio {
namespace {

std::string Name(const ros::NodeHandle& pnh, const std::string& name) {
  return pnh.resolveName(name);
}

ParamError Missing(const ros::NodeHandle& pnh, const std::string& name) {
  return ParamError(Name(pnh, name) + ": missing; this parameter is required");
}

std::string Range(double lo, double hi, double value) {
  std::ostringstream s;
  s << "expected a number in [" << lo << ", " << hi << "], got " << value;
  return s.str();
}

// Where `word` first stands alone in `text` (not inside a longer name), or npos.
std::size_t FindWord(const std::string& text, const std::string& word) {
  const auto name_char = [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; };
  for (std::size_t at = text.find(word); at != std::string::npos; at = text.find(word, at + 1)) {
    const std::size_t end = at + word.size();
    if ((at == 0 || !name_char(text[at - 1])) && (end == text.size() || !name_char(text[end]))) return at;
  }
  return std::string::npos;
}

}  // namespace

ParamError OptionParamError(const ros::NodeHandle& pnh, const std::string& field, const std::string& problem) {
  // (A name with brackets is no ROS name: only the list's name is resolved.)
  const std::size_t entry = field.find('[');
  return ParamError(Name(pnh, field.substr(0, entry)) + (entry == std::string::npos ? "" : field.substr(entry)) +
                    ": " + problem);
}

void CheckOptionParams(const ros::NodeHandle& pnh, const std::vector<std::string>& fields,
                       const std::function<void()>& check) {
  try {
    check();
  } catch (const std::invalid_argument& e) {
    const std::string problem = e.what();
    const std::string* named = fields.size() == 1 ? &fields.front() : nullptr;
    std::size_t first = std::string::npos;
    for (const std::string& field : fields) {
      const std::size_t at = FindWord(problem, field);
      if (at < first) {
        first = at;
        named = &field;
      }
    }
    if (!named) throw ParamError(pnh.getNamespace() + ": " + problem);
    throw OptionParamError(pnh, *named, problem);
  }
}

double NumberParam(const ros::NodeHandle& pnh, const std::string& name, double fallback) {
  return OptionalNumberParam(pnh, name).value_or(fallback);
}

std::optional<double> OptionalNumberParam(const ros::NodeHandle& pnh, const std::string& name) {
  if (!pnh.hasParam(name)) return std::nullopt;
  double value = 0.0;
  int as_int = 0;
  if (!pnh.getParam(name, value)) {
    if (!pnh.getParam(name, as_int)) throw ParamError(Name(pnh, name) + ": expected a number");
    value = as_int;
  }
  return value;
}

double NumberParam(const ros::NodeHandle& pnh, const std::string& name, double fallback, double lo,
                   double hi) {
  if (!pnh.hasParam(name)) return fallback;
  const double value = NumberParam(pnh, name, fallback);
  if (!std::isfinite(value) || value < lo || value > hi) {
    throw ParamError(Name(pnh, name) + ": " + Range(lo, hi, value));
  }
  return value;
}

int IntParam(const ros::NodeHandle& pnh, const std::string& name, int fallback) {
  if (!pnh.hasParam(name)) return fallback;
  int value = 0;
  if (!pnh.getParam(name, value)) throw ParamError(Name(pnh, name) + ": expected a whole number");
  return value;
}

std::vector<std::string> StringListParam(const ros::NodeHandle& pnh, const std::string& name,
                                         const std::string& expected) {
  std::vector<std::string> value;
  if (pnh.hasParam(name) && !pnh.getParam(name, value)) throw ParamError(Name(pnh, name) + ": expected " + expected);
  return value;
}

int IntParam(const ros::NodeHandle& pnh, const std::string& name, int fallback, int lo, int hi) {
  if (!pnh.hasParam(name)) return fallback;
  const int value = IntParam(pnh, name, fallback);
  if (value < lo || value > hi) {
    throw ParamError(Name(pnh, name) + ": expected a whole number in [" + std::to_string(lo) +
                     ", " + std::to_string(hi) + "], got " + std::to_string(value));
  }
  return value;
}

std::string StringParam(const ros::NodeHandle& pnh, const std::string& name,
                        const std::string& fallback) {
  if (!pnh.hasParam(name)) return fallback;
  std::string value;
  if (!pnh.getParam(name, value)) throw ParamError(Name(pnh, name) + ": expected a string");
  return value;
}

double PositiveParam(const ros::NodeHandle& pnh, const std::string& name, double fallback,
                     double hi) {
  const double value = NumberParam(pnh, name, fallback, -hi, hi);
  if (!(value > 0.0)) {
    std::ostringstream s;
    s << Name(pnh, name) << ": expected a number in (0, " << hi << "], got " << value;
    throw ParamError(s.str());
  }
  return value;
}

bool BoolParam(const ros::NodeHandle& pnh, const std::string& name, bool fallback) {
  if (!pnh.hasParam(name)) return fallback;
  bool value = false;
  if (!pnh.getParam(name, value)) throw ParamError(Name(pnh, name) + ": expected true or false");
  return value;
}

std::string RequiredStringParam(const ros::NodeHandle& pnh, const std::string& name) {
  const std::string value = StringParam(pnh, name, "");
  if (value.empty()) throw Missing(pnh, name);
  return value;
}

int RequiredIntParam(const ros::NodeHandle& pnh, const std::string& name, int lo, int hi) {
  if (!pnh.hasParam(name)) throw Missing(pnh, name);
  return IntParam(pnh, name, lo, lo, hi);
}

std::vector<int> RequiredIntListParam(const ros::NodeHandle& pnh, const std::string& name, int lo,
                                      int hi) {
  if (!pnh.hasParam(name)) throw Missing(pnh, name);
  XmlRpc::XmlRpcValue value;
  pnh.getParam(name, value);
  const std::string expected = "expected a non-empty list of whole numbers in [" + std::to_string(lo) + ", " +
                               std::to_string(hi) + "], such as [100, 101]";
  std::vector<int> out;
  auto add = [&](XmlRpc::XmlRpcValue& item) {
    if (item.getType() != XmlRpc::XmlRpcValue::TypeInt) throw ParamError(Name(pnh, name) + ": " + expected);
    const int v = static_cast<int>(item);
    if (v < lo || v > hi) {
      throw ParamError(Name(pnh, name) + ": " + expected + "; got " + std::to_string(v));
    }
    out.push_back(v);
  };
  if (value.getType() == XmlRpc::XmlRpcValue::TypeArray) {
    for (int i = 0; i < value.size(); ++i) add(value[i]);
  } else {
    add(value);
  }
  if (out.empty()) throw ParamError(Name(pnh, name) + ": " + expected + "; got an empty list");
  return out;
}

}  // namespace multirobot_audio
