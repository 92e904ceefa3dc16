#!/usr/bin/env node
// Runs the Khronos glTF-Validator (npm package gltf-validator, installed by
// scripts/fetch_gltf_validator into .cache/gltf-validator/) on one .glb or .gltf file and prints
// one line of JSON:
//   {"file": …, "validatorVersion": …, "numErrors": E, "numWarnings": W, "numInfos": I,
//    "numHints": H, "truncated": bool, "messages": [{"code", "severity", "pointer", "message"}…]}
// (severity 0 error, 1 warning, 2 info, 3 hint; at most 50 messages listed).
// Exit codes: 0 no errors, 1 the validator found errors, 2 bad usage or the validator is missing.
//
//   node tools/validate_gltf.mjs FILE.glb
// The environment variable MYO_GLTF_VALIDATOR_DIR overrides the install folder (.cache/gltf-validator).
import { readFileSync } from "node:fs";
import { createRequire } from "node:module";
import path from "node:path";
import { fileURLToPath } from "node:url";

const here = path.dirname(fileURLToPath(import.meta.url));
const installDir = process.env.MYO_GLTF_VALIDATOR_DIR || path.join(here, "..", ".cache", "gltf-validator");

if (process.argv.length !== 3) {
  console.error("usage: node tools/validate_gltf.mjs FILE.glb|FILE.gltf");
  process.exit(2);
}
const file = process.argv[2];

let validator;
try {
  const require = createRequire(path.join(path.resolve(installDir), "package.json"));
  validator = require("gltf-validator");
} catch (e) {
  console.error(`validate_gltf: gltf-validator not found in ${installDir} (run scripts/fetch_gltf_validator)`);
  process.exit(2);
}

let bytes;
try {
  bytes = new Uint8Array(readFileSync(file));
} catch (e) {
  console.error(`validate_gltf: cannot read ${file}: ${e.message}`);
  process.exit(2);
}

// External resources (a .gltf's .bin or images) are read from beside the file.
const externalResourceFunction = (uri) =>
  new Promise((resolve, reject) => {
    try {
      resolve(new Uint8Array(readFileSync(path.resolve(path.dirname(file), decodeURIComponent(uri)))));
    } catch (e) {
      reject(e.toString());
    }
  });

try {
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 0,
    writeTimestamp: false,
    externalResourceFunction,
  });
  const issues = report.issues;
  const out = {
    file,
    validatorVersion: report.validatorVersion,
    numErrors: issues.numErrors,
    numWarnings: issues.numWarnings,
    numInfos: issues.numInfos,
    numHints: issues.numHints,
    truncated: issues.truncated,
    messages: issues.messages.slice(0, 50).map((m) => ({
      code: m.code,
      severity: m.severity,
      pointer: m.pointer ?? null,
      message: m.message,
    })),
  };
  console.log(JSON.stringify(out));
  process.exit(issues.numErrors > 0 ? 1 : 0);
} catch (e) {
  console.error(`validate_gltf: the validator could not read ${file}: ${e}`);
  process.exit(2);
}
