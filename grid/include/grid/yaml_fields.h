#pragma once

#include <initializer_list>
#include <string>
#include <vector>

#include <yaml-cpp/yaml.h>

namespace grid {

// Typed reads of YAML fields that fail with an InputError naming the file and the field
// (e.g. "robots[2].pose"), so every config file in the project reports errors the same way.
class YamlFields {
 public:
  // Parses `file`; `what` names the kind of file in errors ("map file", "world file").
  static YamlFields Load(const std::string& file, const std::string& what);

  // A view of a nested mapping; `path` is the field path used in messages.
  YamlFields(std::string file, YAML::Node node, std::string path);

  const std::string& file() const { return file_; }
  const YAML::Node& node() const { return node_; }

  // Throws unless the node is a mapping whose keys all appear in `known`.
  void ExpectOnlyKeys(std::initializer_list<const char*> known) const;
  bool Has(const std::string& key) const { return static_cast<bool>(node_[key]); }

  double Number(const std::string& key) const;
  double Number(const std::string& key, double fallback) const;
  std::string String(const std::string& key) const;
  std::string String(const std::string& key, const std::string& fallback) const;
  // A sequence of exactly `n` numbers, such as a pose [x, y, yaw].
  std::vector<double> Numbers(const std::string& key, std::size_t n, const char* shape) const;
  // Each element of a sequence field (absent -> empty) as a mapping view.
  std::vector<YamlFields> Elements(const std::string& key) const;
  YamlFields Child(const std::string& key) const;

  // The dotted path of `key` within this view, for messages.
  std::string FieldName(const std::string& key) const;
  [[noreturn]] void Fail(const std::string& key, const std::string& problem) const;

 private:
  std::string file_;
  YAML::Node node_;
  std::string path_;
};

}  // namespace grid
