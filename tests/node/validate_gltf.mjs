// Validate a glTF/GLB file with the Khronos glTF-Validator and print a JSON summary:
//   node validate_gltf.mjs FILE
// -> {"errors": n, "warnings": n, "infos": n, "hints": n, "messages": [{code, severity, message, pointer}]}
// severity: 0 error, 1 warning, 2 info, 3 hint. Exit code 0 unless the file cannot be read.
import { readFileSync } from "node:fs";
import { createRequire } from "node:module";
import { basename } from "node:path";

const require = createRequire(import.meta.url);
const validator = require("gltf-validator");

const file = process.argv[2];
if (!file) {
  console.error("usage: node validate_gltf.mjs FILE");
  process.exit(2);
}
const bytes = new Uint8Array(readFileSync(file));
const report = await validator.validateBytes(bytes, {
  uri: basename(file),
  maxIssues: 1000,
  externalResourceFunction: () => Promise.reject(new Error("external resources are not allowed")),
});
const issues = report.issues;
console.log(JSON.stringify({
  validator: report.validatorVersion,
  errors: issues.numErrors,
  warnings: issues.numWarnings,
  infos: issues.numInfos,
  hints: issues.numHints,
  messages: issues.messages.map(({ code, severity, message, pointer }) => ({ code, severity, message, pointer })),
  info: report.info ?? null,
}));
