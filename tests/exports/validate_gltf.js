// Runs the Khronos glTF Validator (npm gltf-validator) on each file given and
// prints one JSON report per line: {"file", "errors", "warnings", "messages"}.
// Exit code 0; the Python test judges the reports.
const fs = require("fs");
const validator = require("gltf-validator");

async function main() {
  for (const file of process.argv.slice(2)) {
    const data = new Uint8Array(fs.readFileSync(file));
    const report = await validator.validateBytes(data, {
      uri: file,
      maxIssues: 0,
      externalResourceFunction: (uri) =>
        Promise.reject(new Error(`external resource ${uri} not expected`)),
    });
    const messages = report.issues.messages.map((m) => ({
      code: m.code, severity: m.severity, pointer: m.pointer, message: m.message,
    }));
    console.log(JSON.stringify({
      file,
      errors: report.issues.numErrors,
      warnings: report.issues.numWarnings,
      messages,
    }));
  }
}

main().catch((e) => {
  console.error(e);
  process.exit(2);
});
