// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Validates .glb/.gltf files with the Khronos glTF validator (npm package
// `gltf-validator`). Usage: node validate_gltf.js FILE_OR_FOLDER... (a folder:
// every .glb under it, sorted). --strict: a warning fails a file too.
// Exit codes: 0 all valid (no errors), 1 a file has errors (or, with
// --strict, warnings), 2 the validator or a file is missing. Infos (such as
// an extension the validator cannot check) are printed, never fatal.
'use strict';
const fs = require('fs');
const path = require('path');

let validator;
try {
    validator = require('gltf-validator');
} catch (e) {
    console.error('validate_gltf: the npm package gltf-validator is not installed where node looks for it ' +
                  '(NODE_PATH=' + (process.env.NODE_PATH || '') + '): ' + e.message);
    process.exit(2);
}

let strict = false;

async function validate(file) {
    const bytes = new Uint8Array(fs.readFileSync(file));
    const report = await validator.validateBytes(bytes, {
        uri: path.basename(file),
        maxIssues: 50,
        externalResourceFunction: (uri) => Promise.reject(new Error('external resource ' + uri + ' not allowed')),
    });
    const issues = report.issues;
    console.log(file + ': ' + issues.numErrors + ' errors, ' + issues.numWarnings + ' warnings, ' + issues.numInfos +
                ' infos (' + (report.info ? report.info.totalTriangleCount + ' triangles' : 'no info') + ')');
    for (const m of issues.messages) {
        if (m.severity <= 1) console.log('  ' + ['error', 'warning'][m.severity] + ' ' + m.code + ' ' + m.pointer + ': ' + m.message);
    }
    return issues.numErrors + (strict ? issues.numWarnings : 0);
}

(async () => {
    const files = [];
    const walk = (dir) => {
        for (const name of fs.readdirSync(dir).sort()) {
            const full = path.join(dir, name);
            if (fs.statSync(full).isDirectory()) walk(full);
            else if (name.endsWith('.glb')) files.push(full);
        }
    };
    for (const arg of process.argv.slice(2)) {
        if (arg === '--strict') {
            strict = true;
            continue;
        }
        if (fs.existsSync(arg) && fs.statSync(arg).isDirectory()) walk(arg);
        else files.push(arg);
    }
    if (files.length === 0) {
        console.error('usage: node validate_gltf.js FILE...');
        process.exit(2);
    }
    let failed = 0;
    for (const file of files) {
        if (!fs.existsSync(file)) {
            console.error('validate_gltf: ' + file + ' does not exist');
            process.exit(2);
        }
        if ((await validate(file)) > 0) failed++;
    }
    process.exit(failed > 0 ? 1 : 0);
})().catch((e) => {
    console.error('validate_gltf: ' + e.message);
    process.exit(2);
});
