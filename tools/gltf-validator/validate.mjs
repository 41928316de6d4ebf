// Validates one .glb with the Khronos glTF-Validator and prints the report's issue summary
// as JSON. Exit code: 0 when the file has no errors, 1 when it has errors, 2 on bad usage.
//
// Install once:  npm ci --prefix tools/gltf-validator
// Run:           node tools/gltf-validator/validate.mjs model.glb

import { readFile } from 'node:fs/promises';
import { basename } from 'node:path';
import validator from 'gltf-validator';

const path = process.argv[2];
if (!path) {
  console.error('usage: node validate.mjs FILE.glb');
  process.exit(2);
}

let bytes;
try {
  bytes = new Uint8Array(await readFile(path));
} catch (err) {
  console.error(`cannot read ${path}: ${err.message}`);
  process.exit(2);
}

const report = await validator.validateBytes(bytes, {
  uri: basename(path),
  format: 'glb',
  maxIssues: 0,
  writeTimestamp: false,
});

const { issues, info } = report;
console.log(
  JSON.stringify(
    {
      uri: report.uri,
      validatorVersion: report.validatorVersion,
      numErrors: issues.numErrors,
      numWarnings: issues.numWarnings,
      numInfos: issues.numInfos,
      numHints: issues.numHints,
      truncated: issues.truncated,
      messages: issues.messages,
      info,
    },
    null,
    2,
  ),
);
process.exit(issues.numErrors > 0 ? 1 : 0);
