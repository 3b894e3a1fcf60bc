// Validates a glTF 2.0 file (GLB or JSON glTF) with the Khronos glTF validator (npm
// `gltf-validator`, installed in tools/oracles/node_modules by setup.sh) and prints its JSON
// report on stdout: `issues.numErrors`, `numWarnings`, `numInfos`, `numHints` and the
// messages. Exits 0 when the validator ran (whatever it found), 1 when it could not.
// Used by semsim's export tests (crates/interop/tests/export_gltf.rs). Usage:
//
//     node tools/oracles/validate_gltf.mjs FILE.glb
import { readFile } from 'node:fs/promises';
import { createRequire } from 'node:module';
import path from 'node:path';

const require = createRequire(import.meta.url);
const validator = require('gltf-validator');

const file = process.argv[2];
if (!file) {
  console.error('usage: node validate_gltf.mjs FILE.glb');
  process.exit(2);
}

try {
  const bytes = new Uint8Array(await readFile(file));
  const report = await validator.validateBytes(bytes, {
    uri: path.basename(file),
    maxIssues: 200,
    writeTimestamp: false,
    // A GLB has no external resources; a .gltf's are read from beside it.
    externalResourceFunction: (uri) =>
      readFile(path.resolve(path.dirname(file), decodeURIComponent(uri))).then(
        (data) => new Uint8Array(data),
      ),
  });
  console.log(JSON.stringify(report, null, 1));
} catch (error) {
  console.error(`validate_gltf: ${file}: ${error}`);
  process.exit(1);
}
