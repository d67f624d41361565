#pragma once
// One trial's results as one line of words that reads back to the very same values: whole
// numbers as they are, doubles in the shortest text that reads back bit for bit (infinities and
// NaN included). A batch tool makes its report from records read
// back, in a whole run as in a merge of shards, so the two reports cannot differ.
#include <cstdint>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

namespace multirobot_audio::tools {

class RecordWriter {
 public:
  template <class T>
  RecordWriter& Put(T value) {
    static_assert(std::is_arithmetic_v<T>, "records hold numbers: cast enums to int");
    if constexpr (std::is_same_v<T, bool>) {
      PutUnsigned(value ? 1 : 0);
    } else if constexpr (std::is_floating_point_v<T>) {
      PutDouble(value);
    } else if constexpr (std::is_signed_v<T>) {
      PutSigned(value);
    } else {
      PutUnsigned(value);
    }
    return *this;
  }
  // The count, then the values.
  template <class T>
  RecordWriter& PutList(const std::vector<T>& values) {
    Put(values.size());
    for (const T& v : values) Put(v);
    return *this;
  }
  const std::string& text() const { return text_; }

 private:
  void PutDouble(double value);
  void PutSigned(long long value);
  void PutUnsigned(unsigned long long value);
  void Word(const char* word);
  std::string text_;
};

// Reads a record's words in the order they were put. Every error throws std::runtime_error
// naming `where` (the file and line), the word's position and what was expected.
class RecordReader {
 public:
  RecordReader(const std::string& text, std::string where);

  template <class T>
  T Get() {
    static_assert(std::is_arithmetic_v<T>, "records hold numbers: read enums as int");
    if constexpr (std::is_same_v<T, bool>) {
      return GetUnsigned(1) == 1;
    } else if constexpr (std::is_floating_point_v<T>) {
      return static_cast<T>(GetDouble());
    } else if constexpr (std::is_signed_v<T>) {
      return static_cast<T>(GetSigned(std::numeric_limits<T>::min(), std::numeric_limits<T>::max()));
    } else {
      return static_cast<T>(GetUnsigned(std::numeric_limits<T>::max()));
    }
  }
  // A whole number from lo to hi (an enum's values, say).
  long long GetInRange(long long lo, long long hi) { return GetSigned(lo, hi); }
  // A count of things that follow, each of `words` words: no more than the words left, so that
  // a damaged count fails here and not in a huge allocation.
  std::size_t GetCount(std::size_t words = 1) {
    const std::size_t left = next_ < words_.size() ? words_.size() - next_ - 1 : 0;
    return GetUnsigned(left / words);
  }
  template <class T>
  std::vector<T> GetList() {
    std::vector<T> values(GetCount());
    for (T& v : values) v = Get<T>();
    return values;
  }
  // Reads a value that must equal `expected` (a seed the options determine, say).
  template <class T>
  void Expect(T expected, const std::string& name) {
    const T value = Get<T>();
    if (value != expected) Fail(name + " " + std::to_string(expected), std::to_string(value));
  }
  // Throws unless every word has been read.
  void End() const;

 private:
  double GetDouble();
  long long GetSigned(long long lo, long long hi);
  unsigned long long GetUnsigned(unsigned long long hi);
  const std::string& Next(const char* what);
  [[noreturn]] void Fail(const std::string& expected, const std::string& got) const;

  std::vector<std::string> words_;
  std::size_t next_ = 0;
  std::string where_;
};

}  // namespace multirobot_audio::tools
