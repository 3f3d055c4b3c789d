// Tests of case identity (lub/sweep/hash.hpp): SHA-256 against the FIPS 180-4 examples,
// and the canonical JSON text that makes equal scenes hash equal.
#include "lub/sweep/hash.hpp"

#include <gtest/gtest.h>

#include <string>

using lub::sweep::canonical_json;
using lub::sweep::scene_hash;
using lub::sweep::sha256_hex;
using nlohmann::json;

TEST(SweepHash, Sha256KnownVectors) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256_hex(std::string(1000000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
  // Padding edge cases: 55, 56 and 64 bytes (one or two final blocks).
  EXPECT_EQ(sha256_hex(std::string(55, 'a')), "9f4390f8d30c2dd92ec9f095b65e2b9ae9b0a925a5258e241c9f1e910f734318");
  EXPECT_EQ(sha256_hex(std::string(56, 'a')), "b35439a4ac6f0948b6d6f9e3c6af0f5f590ce20f1bde7090ef7970686ec6738a");
  EXPECT_EQ(sha256_hex(std::string(64, 'a')), "ffe054fe7ae0cb6dc65c3af9b61d5209f439851db43d0ba5997337df154668eb");
}

TEST(SweepHash, CanonicalTextIgnoresKeyOrderSpacingAndNumberSpelling) {
  const json a = json::parse(R"({"b": 1, "a": {"y": [1.0, 2.5], "x": "s"}})");
  const json b = json::parse(R"({ "a" : { "x" : "s", "y" : [ 1, 2.50 ] }, "b" : 1.0 })");
  EXPECT_EQ(canonical_json(a), R"({"a":{"x":"s","y":[1,2.5]},"b":1})");
  EXPECT_EQ(canonical_json(a), canonical_json(b));
  EXPECT_EQ(scene_hash(a), scene_hash(b));
  EXPECT_EQ(scene_hash(a), sha256_hex(canonical_json(a)));
}

TEST(SweepHash, CanonicalTextKeepsEveryBit) {
  // Shortest round-trip form: reading the text back gives the same double.
  for (double x : {0.1, 0.0095, 1e-300, 6.02214076e23, 0.1 + 0.2, -2.5e-8}) {
    const std::string t = canonical_json(json(x));
    EXPECT_EQ(json::parse(t).get<double>(), x) << t;
  }
  EXPECT_NE(scene_hash(json(0.1 + 0.2)), scene_hash(json(0.3)));
  EXPECT_EQ(canonical_json(json(-0.0)), "-0.0");  // its sign is kept
  EXPECT_EQ(canonical_json(json(1e300)), "1e+300");  // too large to be an exact integer
  EXPECT_EQ(canonical_json(json(-4.0)), "-4");
}

TEST(SweepHash, DifferentScenesDifferentHashes) {
  const json a = {{"viscosity_Pa_s", 0.4}};
  const json b = {{"viscosity_Pa_s", 0.40000000000000002}};  // the same double
  const json c = {{"viscosity_Pa_s", 0.4000000000000001}};
  EXPECT_EQ(scene_hash(a), scene_hash(b));
  EXPECT_NE(scene_hash(a), scene_hash(c));
  EXPECT_EQ(scene_hash(a).size(), 64u);
}
