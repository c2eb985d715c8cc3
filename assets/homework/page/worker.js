// The browser's host for a student's page: src/homework/page/worker.rs starts this in a
// dedicated Worker of its own, posts it one message (JSON: {nonce, prelude: [[name, text] or
// [name, null, url] for a library the page serves], input}) and reads back what driver.js
// returns. Each script runs as a classic script
// (importScripts of its text, named by a sourceURL), so its top-level classes and `let`s are
// global as in the student's own page. Everything this needs is taken before any script runs:
// browser.js then takes the Worker's network, its other workers and its channel away.
"use strict";

(function () {
    const post = self.postMessage.bind(self);
    const fetchPage = self.fetch.bind(self);
    const load = self.importScripts.bind(self);
    const makeUrl = URL.createObjectURL.bind(URL);
    const revokeUrl = URL.revokeObjectURL.bind(URL);
    const BlobClass = Blob;
    const FunctionClass = Function;
    const SyntaxErrorClass = SyntaxError;
    const parse = JSON.parse;
    const stringify = JSON.stringify;
    const then = Promise.prototype.then;
    const clock = performance.now.bind(performance);
    let started = 0;
    let nonce = "";

    // The message of compiling `text` as a function body (not run), or null where it compiles.
    function compileError(text) {
        try {
            new FunctionClass(text);
            return null;
        } catch (e) {
            return String(e && e.message);
        }
    }

    // The browser tells a script's syntax error without its line: the line is the first whose
    // prefix of the script fails as the whole script does.
    function syntaxLine(text) {
        const lines = text.split("\n");
        const whole = compileError(text);
        if (whole === null) return 0;
        let [low, high] = [1, lines.length];
        while (low < high) {
            const mid = (low + high) >> 1;
            if (compileError(lines.slice(0, mid).join("\n")) === whole) high = mid;
            else low = mid + 1;
        }
        return low;
    }

    function evalScript(name, text) {
        post(stringify({ nonce, running: name }));
        const url = makeUrl(new BlobClass([text + "\n//# sourceURL=" + name], { type: "text/javascript" }));
        try {
            load(url);
        } catch (e) {
            const stack = String((e && e.stack) || "");
            if (e instanceof SyntaxErrorClass && !stack.includes(name + ":")) {
                const message = String(e.message).replace(/^Failed to execute 'importScripts' on '\w+': /, "");
                const located = new SyntaxErrorClass(message);
                located.stack = "SyntaxError: " + message + "\n    at " + name + ":" + syntaxLine(text) + ":1";
                throw located;
            }
            throw e;
        } finally {
            revokeUrl(url);
        }
    }

    function step(file, what) {
        post(stringify({ nonce, running: file, what }));
    }

    // A library the page serves, as text (before any script runs: nothing has been taken yet).
    async function served(name, url) {
        const response = await fetchPage(url);
        if (!response.ok) throw new Error("the page could not load " + name + " (" + url + ": " + response.status + ")");
        return response.text();
    }

    self.onmessage = async function (event) {
        self.onmessage = null;
        const message = parse(event.data);
        nonce = message.nonce;
        started = clock();
        let prelude;
        try {
            prelude = await Promise.all(message.prelude.map(async ([name, text, url]) => [name, text === null ? await served(name, url) : text]));
        } catch (e) {
            post(stringify({ nonce, failed: { file: "shadowlab", line: 0, message: String(e && e.message) } }));
            return;
        }
        for (const [name, text] of prelude) {
            try {
                evalScript(name, text);
            } catch (e) {
                post(stringify({ nonce, failed: { file: name, line: 0, message: String(e && e.message) } }));
                return;
            }
        }
        const running = globalThis.__shadowlab.runPage({ evalScript, step, elapsedMs: () => clock() - started, engine: "browser" }, message.input);
        then.call(
            running,
            (output) => post(stringify({ nonce, output })),
            (e) => post(stringify({ nonce, failed: { file: "shadowlab/driver.js", line: 0, message: String(e && e.message) } })),
        );
    };
})();
