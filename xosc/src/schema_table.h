#pragma once

// Internal: the per-type rules of the OpenSCENARIO schema (see schema.cpp).

#include <cstddef>
#include <cstdint>
#include <iterator>
#include <string_view>

#include "corsa/xosc/schema.h"

namespace corsa::xosc {

/// A name of the schema table: a word of its text, by place. The table holds places rather than
/// pointers, so that it is plain read-only data (no relocation written at every start).
struct SchemaWord {
  uint16_t start = 0;
  uint16_t size = 0;
};

/// The word's text.
std::string_view schema_word(SchemaWord word);

/// A run of the table's names, read as string_views.
class SchemaNames {
 public:
  class Iterator {
   public:
    using iterator_category = std::forward_iterator_tag;
    using value_type = std::string_view;
    using difference_type = std::ptrdiff_t;
    using pointer = void;
    using reference = std::string_view;

    Iterator() = default;
    explicit Iterator(const SchemaWord* at) : at_(at) {}
    std::string_view operator*() const { return schema_word(*at_); }
    Iterator& operator++() {
      ++at_;
      return *this;
    }
    Iterator operator++(int) {
      Iterator before = *this;
      ++at_;
      return before;
    }
    bool operator==(const Iterator&) const = default;

   private:
    const SchemaWord* at_ = nullptr;
  };

  SchemaNames(const SchemaWord* first, size_t count) : first_(first), count_(count) {}
  size_t size() const { return count_; }
  bool empty() const { return count_ == 0; }
  std::string_view operator[](size_t i) const { return schema_word(first_[i]); }
  Iterator begin() const { return Iterator(first_); }
  Iterator end() const { return Iterator(first_ + count_); }

 private:
  const SchemaWord* first_;
  size_t count_;
};

struct TypeRule {
  SchemaWord type_word;
  uint16_t child_first = 0;  ///< the children are names child_first.. of the table
  uint16_t child_count = 0;
  uint16_t attribute_first = 0;
  uint16_t attribute_count = 0;

  std::string_view type() const { return schema_word(type_word); }
  SchemaNames children() const;
  SchemaNames attributes() const;
  bool allows_child(std::string_view name) const;
  bool allows_attribute(std::string_view name) const;
};

/// The rule of an XSD complex type, or null when the type is not in the table (our bug).
const TypeRule* find_type_rule(std::string_view type);

}  // namespace corsa::xosc
