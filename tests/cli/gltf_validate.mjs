// gltf_validate.mjs — the Khronos glTF validator (npm package gltf-validator)
// on one .gltf or .glb file, for tests/cli/lightmap.t:
//     node tests/cli/gltf_validate.mjs FILE [VALIDATOR]
// VALIDATOR: the package's folder (default: build/node/node_modules/
// gltf-validator under the current folder; `npm install --prefix build/node
// gltf-validator` puts it there). Prints "errors N", "warnings N", "infos N",
// "hints N", then each error and warning as "# SEVERITY CODE: message
// (pointer)"; exits 0 when there is no error, 1 when there are, 2 when the
// file or the validator cannot be read.
import { createRequire } from 'module';
import { readFileSync } from 'fs';
import { resolve } from 'path';

const [file, folder = 'build/node/node_modules/gltf-validator'] = process.argv.slice(2);
if (!file) {
    console.error('usage: node gltf_validate.mjs FILE [VALIDATOR]');
    process.exit(2);
}
let validator, bytes;
try {
    validator = createRequire(import.meta.url)(resolve(folder));
    bytes = new Uint8Array(readFileSync(file));
} catch (e) {
    console.error(`gltf_validate: ${e.message}`);
    process.exit(2);
}
const severities = ['error', 'warning', 'info', 'hint'];
validator.validateBytes(bytes, { uri: file, maxIssues: 1000 }).then((report) => {
    const issues = report.issues;
    console.log(`errors ${issues.numErrors}\nwarnings ${issues.numWarnings}\n` +
                `infos ${issues.numInfos}\nhints ${issues.numHints}`);
    for (const m of issues.messages)
        if (m.severity <= 1)
            console.log(`# ${severities[m.severity]} ${m.code}: ${m.message} (${m.pointer || ''})`);
    process.exit(issues.numErrors === 0 ? 0 : 1);
}, (e) => {
    console.error(`gltf_validate: ${file}: ${e}`);
    process.exit(2);
});
