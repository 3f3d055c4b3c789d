// Case identity: SHA-256 of a case's effective scene, dumped as canonical JSON.
#pragma once

#include <nlohmann/json.hpp>

#include <string>

namespace lub::sweep {

/// SHA-256 of `data` (FIPS 180-4, computed by OpenSSL's libcrypto), as 64 lower-case hex digits.
std::string sha256_hex(const std::string& data);

/// The canonical text of a JSON document: no whitespace, object keys sorted (nlohmann's
/// `json` keeps objects sorted), integral numbers written as integers (5000.0 → 5000),
/// other numbers in the shortest form that reads back to the same double. Two scenes
/// that read the same have the same text, whatever the key order, spacing or number
/// spelling of their files.
std::string canonical_json(const nlohmann::json& doc);

/// sha256_hex(canonical_json(scene)): the case's identity in a study file (resume).
std::string scene_hash(const nlohmann::json& scene);

}  // namespace lub::sweep
