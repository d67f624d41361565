#include "grid/yaml_fields.h"

#include "grid/file_path.h"
#include "grid/input_error.h"

namespace grid {

YamlFields YamlFields::Load(const std::string& file, const std::string& what) {
  std::string why;
  if (!IsRegularFile(file, &why)) throw InputError(file, "", what + " not found (" + why + ")");
  YAML::Node root;
  try {
    root = YAML::LoadFile(file);
  } catch (const YAML::BadFile&) {
    throw InputError(file, "", "cannot open " + what);
  } catch (const YAML::Exception& e) {
    throw InputError(file, "",
                     "malformed YAML at line " + std::to_string(e.mark.line + 1) + ": " + e.msg);
  }
  if (!root.IsMap()) throw InputError(file, "", what + ": expected a YAML mapping at the top");
  return YamlFields(file, root, "");
}

YamlFields::YamlFields(std::string file, YAML::Node node, std::string path)
    : file_(std::move(file)), node_(std::move(node)), path_(std::move(path)) {}

std::string YamlFields::FieldName(const std::string& key) const {
  return path_.empty() ? key : path_ + "." + key;
}

void YamlFields::Fail(const std::string& key, const std::string& problem) const {
  throw InputError(file_, key.empty() ? path_ : FieldName(key), problem);
}

void YamlFields::ExpectOnlyKeys(std::initializer_list<const char*> known) const {
  if (!node_.IsMap()) Fail("", "expected a mapping");
  std::string list;
  for (const char* k : known) list += (list.empty() ? "" : ", ") + std::string(k);
  for (const auto& kv : node_) {
    // A key may be a list, a mapping or null in YAML; none of ours is.
    if (!kv.first.IsScalar()) {
      Fail("", std::string("expected text keys, got ") +
                   (kv.first.IsSequence() ? "a list" : kv.first.IsMap() ? "a mapping" : "an empty key"));
    }
    const std::string key = kv.first.as<std::string>();
    bool found = false;
    for (const char* k : known) found = found || key == k;
    if (!found) Fail(key, "unknown key; expected one of: " + list);
  }
}

double YamlFields::Number(const std::string& key) const {
  if (!Has(key)) Fail(key, "missing; this field is required");
  try {
    return node_[key].as<double>();
  } catch (const YAML::Exception&) {
    Fail(key, "expected a number");
  }
}

double YamlFields::Number(const std::string& key, double fallback) const {
  return Has(key) ? Number(key) : fallback;
}

std::string YamlFields::String(const std::string& key) const {
  if (!Has(key)) Fail(key, "missing; this field is required");
  if (!node_[key].IsScalar()) Fail(key, "expected a string");
  return node_[key].as<std::string>();
}

std::string YamlFields::String(const std::string& key, const std::string& fallback) const {
  return Has(key) ? String(key) : fallback;
}

std::vector<double> YamlFields::Numbers(const std::string& key, std::size_t n,
                                        const char* shape) const {
  if (!Has(key)) Fail(key, std::string("missing; expected ") + shape);
  const YAML::Node seq = node_[key];
  if (!seq.IsSequence() || seq.size() != n) Fail(key, std::string("expected ") + shape);
  std::vector<double> out;
  for (std::size_t i = 0; i < n; ++i) {
    try {
      out.push_back(seq[i].as<double>());
    } catch (const YAML::Exception&) {
      Fail(key, std::string("expected ") + shape + " of numbers");
    }
  }
  return out;
}

std::vector<YamlFields> YamlFields::Elements(const std::string& key) const {
  std::vector<YamlFields> out;
  if (!Has(key)) return out;
  const YAML::Node seq = node_[key];
  if (!seq.IsSequence()) Fail(key, "expected a list");
  for (std::size_t i = 0; i < seq.size(); ++i) {
    out.emplace_back(file_, seq[i], FieldName(key) + "[" + std::to_string(i) + "]");
  }
  return out;
}

YamlFields YamlFields::Child(const std::string& key) const {
  return YamlFields(file_, node_[key], FieldName(key));
}

}  // namespace grid
