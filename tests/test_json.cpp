// the JSON files' builder and layout (src/io/json.cpp): nlohmann-json's document and string escaping,
// rootsim's numbers and indentation
#include <doctest/doctest.h>

#include <cmath>
#include <limits>
#include <string>

#include <nlohmann/json.hpp>

#include "rootsim/json.hpp"

using namespace rootsim;

TEST_CASE("Json: the layout is one member a line, two spaces a level, arrays of objects and empty containers included") {
  Json inner;
  inner.num("a", 0.5).integer("b", -3);
  Json e1, e2;
  e1.str("k", "v");
  const std::string text = Json()
                               .num("x", 2.0)
                               .object("o", inner)
                               .array("list", {e1, e2})
                               .array("none", {})
                               .object("empty", Json())
                               .boolean("f", false)
                               .dump();
  CHECK(text ==
        "{\n"
        "  \"x\": 2,\n"
        "  \"o\": {\n"
        "    \"a\": 0.5,\n"
        "    \"b\": -3\n"
        "  },\n"
        "  \"list\": [\n"
        "    {\n"
        "      \"k\": \"v\"\n"
        "    },\n"
        "    {\n"
        "    }\n"
        "  ],\n"
        "  \"none\": [],\n"
        "  \"empty\": {\n"
        "  },\n"
        "  \"f\": false\n"
        "}");
  CHECK(Json().dump(4) == "{\n    }");
}

TEST_CASE("Json: numbers are numberText's shortest round-trip text, non-finite ones null") {
  const double third = 1.0 / 3.0;
  Json j;
  j.num("third", third).num("tiny", 1e-7).num("big", 1e300).num("int", 100000.0).num("nan", std::nan(""))
      .num("inf", -std::numeric_limits<double>::infinity()).integer("max", 9007199254740993LL);
  const std::string text = j.dump();
  CHECK(text.find("\"third\": 0.3333333333333333,") != std::string::npos);
  CHECK(text.find("\"tiny\": 1e-07,") != std::string::npos);
  CHECK(text.find("\"big\": 1e+300,") != std::string::npos);
  CHECK(text.find("\"int\": 1e+05,") != std::string::npos);
  CHECK(text.find("\"nan\": null,") != std::string::npos);
  CHECK(text.find("\"inf\": null,") != std::string::npos);
  CHECK(text.find("\"max\": 9007199254740993\n") != std::string::npos);
  // and the text reads back to the same values
  const nlohmann::json back = nlohmann::json::parse(text);
  CHECK(back["third"].get<double>() == third);
  CHECK(back["tiny"].get<double>() == 1e-7);
  CHECK(back["max"].get<long long>() == 9007199254740993LL);
  CHECK(back["nan"].is_null());
}

TEST_CASE("Json: strings and keys are escaped, invalid UTF-8 is replaced, and the text parses") {
  Json j;
  j.str("q\"k", "a\"b\\c\nd\te\x01").str("utf8", "\xCE\xB2 = 1").str("bad", std::string("x\xFFy"));
  const std::string text = j.dump();
  CHECK(text.find(R"("q\"k": "a\"b\\c\nd\te\u0001")") != std::string::npos);
  CHECK(text.find("\"utf8\": \"\xCE\xB2 = 1\"") != std::string::npos);
  CHECK(text.find("\"bad\": \"x\xEF\xBF\xBDy\"") != std::string::npos);  // U+FFFD
  const nlohmann::json back = nlohmann::json::parse(text);
  CHECK(back["q\"k"].get<std::string>() == "a\"b\\c\nd\te\x01");
}

TEST_CASE("Json: a key given twice keeps its first place and its last value") {
  const std::string text = Json().integer("a", 1).integer("b", 2).integer("a", 3).dump();
  CHECK(text == "{\n  \"a\": 3,\n  \"b\": 2\n}");
}

TEST_CASE("jsonText: compact text has no spaces and the same numbers") {
  nlohmann::ordered_json v = nlohmann::ordered_json::object();
  v["b"] = nlohmann::ordered_json::array({1, 0.1, static_cast<double>(0.1f), true, nullptr});
  v["a"] = nlohmann::ordered_json::object();
  v["s"] = "x y";
  CHECK(jsonText(v, -1) == R"({"b":[1,0.1,0.10000000149011612,true,null],"a":{},"s":"x y"})");
}

TEST_CASE("theoryJson: every key of the theory block, in order") {
  const std::string text = theoryJson(Theory{}).dump();
  const nlohmann::ordered_json back = nlohmann::ordered_json::parse(text);
  REQUIRE(back.size() == 11);
  CHECK(back.begin().key() == "effective_gain_beta_Lgz_over_R");
  CHECK((--back.end()).key() == "skew_deg_eq15_large_omegaT0");
}
