// The streaming JSON writer: escaping, round-trip doubles, null for non-finite, nesting, misuse.
#include <cmath>
#include <cstdlib>
#include <gtest/gtest.h>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "tacta/json.hpp"

namespace {

using tacta::JsonWriter;

TEST(JsonWriter, EscapesStrings) {
  EXPECT_EQ(JsonWriter::quote("plain"), "\"plain\"");
  EXPECT_EQ(JsonWriter::quote("a\"b\\c"), "\"a\\\"b\\\\c\"");
  EXPECT_EQ(JsonWriter::quote("line\nnext\ttab"), "\"line\\nnext\\ttab\"");
  EXPECT_EQ(JsonWriter::quote(std::string_view("\x01\x1f", 2)), "\"\\u0001\\u001f\"");
  EXPECT_EQ(JsonWriter::quote("módulo µ"), "\"módulo µ\"");  // UTF-8 passes through
}

TEST(JsonWriter, DoublesRoundTripAndNonFiniteIsNull) {
  const double values[] = {0.1, 1.0 / 3.0, -2.5e-300, 6.02214076e23, 1e-3};
  for (const double v : values) EXPECT_EQ(std::strtod(JsonWriter::number(v).c_str(), nullptr), v);
  EXPECT_EQ(JsonWriter::number(std::numeric_limits<double>::quiet_NaN()), "null");
  EXPECT_EQ(JsonWriter::number(std::numeric_limits<double>::infinity()), "null");
  EXPECT_EQ(JsonWriter::number(-std::numeric_limits<double>::infinity()), "null");
}

TEST(JsonWriter, WritesNestedDocumentCompactly) {
  std::ostringstream out;
  {
    JsonWriter json(out, 0);
    json.begin_object();
    json.field("scene", "beam").field("ticks", 1000).field("ok", true);
    json.key("tick_ms").begin_object().field("p50", 0.25).field("max", std::nan("")).end_object();
    json.key("bodies")
        .begin_array()
        .value(1)
        .value("two")
        .null()
        .begin_array()
        .end_array()
        .end_array();
    json.key("empty").begin_object().end_object();
    json.end_object();
    EXPECT_TRUE(json.complete());
  }
  EXPECT_EQ(
      out.str(),
      "{\"scene\":\"beam\",\"ticks\":1000,\"ok\":true,\"tick_ms\":{\"p50\":0.25,\"max\":null},"
      "\"bodies\":[1,\"two\",null,[]],\"empty\":{}}\n");
}

TEST(JsonWriter, IndentsNestedValues) {
  std::ostringstream out;
  {
    JsonWriter json(out, 2);
    json.begin_object().key("a").begin_array().value(1).value(2).end_array().end_object();
  }
  EXPECT_EQ(out.str(), "{\n  \"a\": [\n    1,\n    2\n  ]\n}\n");
}

TEST(JsonWriter, RefusesMisuse) {
  std::ostringstream out;
  JsonWriter json(out);
  json.begin_object();
  EXPECT_THROW(json.value(1), std::logic_error);  // value without key
  EXPECT_THROW(json.end_array(), std::logic_error);
  json.key("k");
  EXPECT_THROW(json.key("again"), std::logic_error);
  EXPECT_THROW(json.end_object(), std::logic_error);  // key waiting for its value
  json.value(3);
  json.end_object();
  EXPECT_THROW(json.begin_array(), std::logic_error);  // a second top-level value
}

}  // namespace
