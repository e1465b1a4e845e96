// Runs the Khronos glTF validator (npm gltf-validator, pinned in tools/package.json) on .glb
// files and fails unless each has 0 errors and 0 warnings. Infos and hints are printed only.
//   node tools/gltf/validate.mjs FILE.glb [FILE.glb ...]
import { readFile } from 'node:fs/promises';
import validator from 'gltf-validator';

let failed = false;
for (const file of process.argv.slice(2)) {
    const bytes = new Uint8Array(await readFile(file));
    const report = await validator.validateBytes(bytes, { maxIssues: 0, format: 'glb' });
    const { numErrors, numWarnings, numInfos, numHints } = report.issues;
    console.log(`${file}: ${numErrors} errors, ${numWarnings} warnings, ${numInfos} infos, ${numHints} hints ` +
        `(validator ${report.validatorVersion}; ${report.info?.drawCallCount} draw calls, ` +
        `${report.info?.animationCount} animations, ${report.info?.totalVertexCount} vertices)`);
    for (const m of report.issues.messages)
        console.log(`  severity ${m.severity} ${m.code} ${m.pointer ?? ''}: ${m.message}`);
    if (numErrors > 0 || numWarnings > 0)
        failed = true;
}
if (process.argv.length < 3) {
    console.error('usage: node tools/gltf/validate.mjs FILE.glb [FILE.glb ...]');
    failed = true;
}
process.exit(failed ? 1 : 0);
