// A reverse proxy as BlueOS puts one before its extensions: the session's server under a path
// prefix, on another origin than the page that frames it (Cockpit's iframe widget, 400 px wide).
// Requests outside the prefix are answered 404 and recorded, so a test can tell that the page
// asked only for relative URLs. Responses stream through as they come (the event stream).
'use strict';
const http = require('http');

class Proxy {
  constructor(target, prefix) {
    this.target = new URL(target);
    this.prefix = prefix;
    this.outsidePrefix = [];
    this.server = http.createServer((request, response) => this.handle(request, response));
  }

  listen() {
    return new Promise((done) => this.server.listen(0, '127.0.0.1', () => done(`http://127.0.0.1:${this.server.address().port}/`)));
  }

  close() { this.server.closeAllConnections(); this.server.close(); }

  handle(request, response) {
    if (request.url === '/') {
      response.writeHead(200, { 'Content-Type': 'text/html' });
      response.end(`<!doctype html><title>Cockpit</title><body style="margin:0">
        <iframe src="${this.prefix}" width="400" height="300" style="border:0"></iframe></body>`);
      return;
    }
    if (!request.url.startsWith(this.prefix)) {
      if (request.url !== '/favicon.ico') this.outsidePrefix.push(request.url);
      response.writeHead(404);
      response.end();
      return;
    }
    const upstream = http.request({
      host: this.target.hostname, port: this.target.port, method: request.method,
      path: `/${request.url.slice(this.prefix.length)}`, headers: { ...request.headers, host: this.target.host },
    }, (answer) => {
      response.writeHead(answer.statusCode, answer.headers);
      answer.pipe(response);
    });
    upstream.on('error', () => { response.writeHead(502); response.end(); });
    request.pipe(upstream);
  }
}

module.exports = { Proxy };
