#include "tool_args/record.h"

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstdlib>
#include <sstream>
#include <stdexcept>

namespace multirobot_audio::tools {

void RecordWriter::Word(const char* word) {
  if (!text_.empty()) text_ += ' ';
  text_ += word;
}

void RecordWriter::PutDouble(double value) {
  // The shortest text that reads back to the same double (36.6, not 36.600000000000001).
  char word[40];
  const auto end = std::to_chars(word, word + sizeof word - 1, value).ptr;
  *end = '\0';
  Word(word);
}

void RecordWriter::PutSigned(long long value) { Word(std::to_string(value).c_str()); }

void RecordWriter::PutUnsigned(unsigned long long value) { Word(std::to_string(value).c_str()); }

RecordReader::RecordReader(const std::string& text, std::string where) : where_(std::move(where)) {
  std::istringstream in(text);
  for (std::string word; in >> word;) words_.push_back(word);
}

const std::string& RecordReader::Next(const char* what) {
  if (next_ >= words_.size()) Fail(what, "the end of the record");
  return words_[next_++];
}

void RecordReader::Fail(const std::string& expected, const std::string& got) const {
  throw std::runtime_error(where_ + ": word " + std::to_string(next_) + ": expected " + expected +
                           ", got " + got);
}

double RecordReader::GetDouble() {
  const std::string& word = Next("a number");
  char* end = nullptr;
  const double value = std::strtod(word.c_str(), &end);
  if (end == word.c_str() || *end) Fail("a number", "'" + word + "'");
  return value;
}

long long RecordReader::GetSigned(long long lo, long long hi) {
  const std::string& word = Next("a whole number");
  char* end = nullptr;
  errno = 0;
  const long long value = std::strtoll(word.c_str(), &end, 10);
  if (end == word.c_str() || *end || errno == ERANGE || value < lo || value > hi)
    Fail("a whole number from " + std::to_string(lo) + " to " + std::to_string(hi), "'" + word + "'");
  return value;
}

unsigned long long RecordReader::GetUnsigned(unsigned long long hi) {
  const std::string& word = Next("a whole number");
  char* end = nullptr;
  errno = 0;
  const unsigned long long value = std::strtoull(word.c_str(), &end, 10);
  // strtoull takes "-1" as the largest value: a sign is never one of ours.
  if (word[0] == '-' || end == word.c_str() || *end || errno == ERANGE || value > hi)
    Fail("a whole number from 0 to " + std::to_string(hi), "'" + word + "'");
  return value;
}

void RecordReader::End() const {
  if (next_ < words_.size())
    throw std::runtime_error(where_ + ": word " + std::to_string(next_ + 1) +
                             ": expected the end of the record, got '" + words_[next_] + "'");
}

}  // namespace multirobot_audio::tools
