// plclab's VS Code extension: starts `plclab lsp` (stdio) for ST, IL, text LD and PLCopen XML.
// Everything else (diagnostics, hover, completion, outline, the TEST code lenses and their
// plclab.runTest command) comes from the server.
"use strict";

const vscode = require("vscode");
const { LanguageClient, TransportKind } = require("vscode-languageclient/node");

let client;

function activate(context) {
  const config = vscode.workspace.getConfiguration("plclab");
  const [command, ...args] = config.get("command", ["plclab", "lsp", "--stdio"]);
  const serverOptions = { command, args, transport: TransportKind.stdio };
  const initializationOptions = { docsUrl: config.get("docsUrl") };
  const dialect = config.get("dialect");
  if (dialect) {
    initializationOptions.dialect = dialect;
  }
  const clientOptions = {
    documentSelector: [
      { scheme: "file", language: "iec-st" },
      { scheme: "untitled", language: "iec-st" },
      { scheme: "file", language: "iec-il" },
      { scheme: "file", language: "iec-ld" },
      { scheme: "file", language: "xml", pattern: "**/*.xml" },
    ],
    initializationOptions,
  };
  client = new LanguageClient("plclab", "plclab", serverOptions, clientOptions);
  client.start();
  context.subscriptions.push({ dispose: () => client && client.stop() });
}

function deactivate() {
  return client ? client.stop() : undefined;
}

module.exports = { activate, deactivate };
