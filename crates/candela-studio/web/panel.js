// The settings form, generated from the server's description of the one
// settings struct (names, help, choices, defaults and this scene's values).
// Only fields the user edits are sent back, as JSON changes; the server
// validates them and answers with the settings error, shown here.
"use strict";
const Panel = {
  // Set by the 3D view and the cell tool, not typed.
  driven: new Set(["eye", "look_at", "up", "fov", "cell"]),
  changes: {},
  build(form, fields, onChange) {
    this.inputs = {};
    for (const f of fields) {
      if (this.driven.has(f.name)) continue;
      const label = document.createElement("label");
      label.title = f.help;
      label.textContent = f.name;
      let input;
      if (typeof f.default === "boolean") {
        input = document.createElement("input");
        input.type = "checkbox";
        input.checked = !!f.value;
        input.read = () => input.checked;
      } else if (f.choices.length) {
        input = document.createElement("select");
        for (const c of f.choices) input.add(new Option(c, c, false, c === f.value));
        input.read = () => input.value;
      } else {
        input = document.createElement("input");
        input.value = f.value === null ? "" : typeof f.value === "string" ? f.value : JSON.stringify(f.value);
        input.placeholder = f.default === null ? "none" : JSON.stringify(f.default);
        input.read = () => parseValue(input.value);
      }
      input.name = f.name;
      input.addEventListener("change", () => {
        this.changes[f.name] = input.read();
        onChange();
      });
      label.appendChild(input);
      form.appendChild(label);
      this.inputs[f.name] = input;
    }
  },
  // Marks the fields a settings error names.
  showError(message) {
    for (const [name, input] of Object.entries(this.inputs))
      input.classList.toggle("bad", !!message && new RegExp("\\b" + name + "\\b").test(message));
  },
};

// A typed value: empty is null (the default), JSON if it parses, else text.
function parseValue(text) {
  const t = text.trim();
  if (t === "") return null;
  try { return JSON.parse(t); } catch (_) { return t; }
}
