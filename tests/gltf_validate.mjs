// Validates glTF/GLB files with the Khronos glTF Validator (npm package gltf-validator) and prints
// one JSON line per file: {"file", "errors", "warnings", "infos", "hints", "messages"} (messages:
// the first error-severity issues as "CODE at POINTER: text"). External files (buffers, images)
// are read relative to the model, so a missing texture is reported as an error.
// Usage: node gltf_validate.mjs NODE_TOOLS_PREFIX FILE...
// Exit code: 0 when no file has errors, 1 when some file has, 2 on bad usage or a crash.
import { createRequire } from 'module';
import fs from 'fs';
import path from 'path';

const [prefix, ...files] = process.argv.slice(2);
if (!prefix || files.length === 0) {
  console.error('usage: node gltf_validate.mjs NODE_TOOLS_PREFIX FILE...');
  process.exit(2);
}
// The validator lives under PREFIX/node_modules (npm install --prefix PREFIX gltf-validator).
const validator = createRequire(path.join(path.resolve(prefix), 'package.json'))('gltf-validator');

let failed = false;
try {
  for (const file of files) {
    const dir = path.dirname(path.resolve(file));
    const report = await validator.validateBytes(new Uint8Array(fs.readFileSync(file)), {
      uri: path.basename(file),
      maxIssues: 0,
      writeTimestamp: false,
      externalResourceFunction: (uri) => new Promise((resolve, reject) => {
        fs.readFile(path.resolve(dir, decodeURIComponent(uri)), (err, data) => {
          if (err) reject(err.toString());
          else resolve(new Uint8Array(data));
        });
      }),
    });
    const issues = report.issues;
    const messages = issues.messages.filter((m) => m.severity === 0).slice(0, 10)
      .map((m) => `${m.code} at ${m.pointer ?? '?'}: ${m.message}`);
    console.log(JSON.stringify({
      file, validator: report.validatorVersion, errors: issues.numErrors, warnings: issues.numWarnings,
      infos: issues.numInfos, hints: issues.numHints, messages,
    }));
    if (issues.numErrors > 0) failed = true;
  }
} catch (e) {
  console.error(`gltf_validate: ${e}`);
  process.exit(2);
}
process.exit(failed ? 1 : 0);
