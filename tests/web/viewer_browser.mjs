// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Opens a bake's web viewer (DIR/viewer/) in headless Chromium driven by
// puppeteer-core (Debian's /usr/bin/chromium, software WebGL through
// SwiftShader) and saves what it draws. Used by tests/web/WebViewerTest.cpp.
//   node viewer_browser.mjs --modules <node_modules> --chromium <path> --dir <bake>
//        --size WxH --out <png> [--query "pos=..&target=..&fov=.."] [--timeout-ms N] [--serve <strata>]
//        [--wait ready|first-frame]
// Serves DIR on 127.0.0.1 with `strata serve DIR --port 0` (--serve; else a
// small static server of its own, for trying a bake by hand), opens
// viewer/index.html?QUERY, waits for window.strataReady (every tile the view
// needs loaded and drawn) and screenshots the canvas. Prints one JSON line:
// { ok, consoleErrors: [...], stats: window.strataStats, pageLoadMs }.
// Exits 1 with a message on any failure (no Chromium, no page, a timeout).

import { createServer } from 'node:http';
import { spawn } from 'node:child_process';
import { readFile, stat } from 'node:fs/promises';
import { existsSync } from 'node:fs';
import { extname, join, normalize, resolve, sep } from 'node:path';
import { pathToFileURL } from 'node:url';

const args = {};
for ( let i = 2; i < process.argv.length; i += 2 ) args[ process.argv[ i ].replace( /^--/, '' ) ] = process.argv[ i + 1 ];
function fail( message ) {

	console.error( `viewer_browser: ${ message }` );
	process.exit( 1 );

}
for ( const key of [ 'modules', 'chromium', 'dir', 'size', 'out' ] ) if ( ! args[ key ] ) fail( `--${ key } is missing` );
if ( args.wait && ! [ 'ready', 'first-frame' ].includes( args.wait ) ) fail( `--wait ${ args.wait }: expected ready or first-frame` );
if ( ! existsSync( args.chromium ) ) fail( `no Chromium at ${ args.chromium }: install Debian's chromium (scripts/install-deps.sh)` );
const root = resolve( args.dir );
if ( ! existsSync( join( root, 'viewer', 'index.html' ) ) ) fail( `${ root }/viewer/index.html does not exist: the bake wrote no viewer` );
const [ width, height ] = args.size.split( 'x' ).map( Number );
const timeoutMs = Number( args[ 'timeout-ms' ] || 45000 );

const puppeteerMain = join( resolve( args.modules ), 'puppeteer-core', 'lib', 'esm', 'puppeteer', 'puppeteer-core.js' );
if ( ! existsSync( puppeteerMain ) ) fail( `puppeteer-core is not installed in ${ args.modules } (npm ci of web/package-lock.json)` );
const puppeteer = ( await import( pathToFileURL( puppeteerMain ).href ) ).default;

// `strata serve DIR --port 0` prints "Serving DIR at http://127.0.0.1:PORT/".
async function strataServe( strata ) {

	const child = spawn( strata, [ 'serve', root, '--port', '0' ], { stdio: [ 'ignore', 'pipe', 'inherit' ] } );
	let text = '';
	const base = await new Promise( ( resolveBase, reject ) => {

		const timer = setTimeout( () => reject( new Error( `strata serve printed no address in 10 s: ${ text }` ) ), 10000 );
		child.stdout.on( 'data', chunk => {

			text += chunk;
			const m = / at (http:\/\/[^ \n]+\/)/.exec( text );
			if ( m ) {

				clearTimeout( timer );
				resolveBase( m[ 1 ] );

			}

		} );
		child.on( 'exit', code => reject( new Error( `strata serve exited (${ code }): ${ text }` ) ) );

	} ).catch( e => fail( String( e.message ) ) );
	return { base, close: () => child.kill( 'SIGINT' ) };

}

const TYPES = { '.html': 'text/html', '.js': 'text/javascript', '.json': 'application/json', '.png': 'image/png', '.glb': 'model/gltf-binary' };
async function ownServer() {

	const server = createServer( async ( request, response ) => {

		const path = normalize( join( root, decodeURIComponent( request.url.split( '?' )[ 0 ] ) ) );
		try {

			if ( path !== root && ! path.startsWith( root + sep ) ) throw new Error( 'outside' );
			if ( ! ( await stat( path ) ).isFile() ) throw new Error( 'not a file' );
			const body = await readFile( path );
			response.writeHead( 200, { 'Content-Type': TYPES[ extname( path ) ] || 'application/octet-stream', 'Content-Length': body.length } );
			response.end( body );

		} catch {

			response.writeHead( 404 );
			response.end();

		}

	} );
	await new Promise( r => server.listen( 0, '127.0.0.1', r ) );
	return { base: `http://127.0.0.1:${ server.address().port }/`, close: () => server.close() };

}
const server = args.serve ? await strataServe( args.serve ) : await ownServer();
const url = `${ server.base }viewer/index.html${ args.query ? '?' + args.query : '' }`;

const consoleErrors = [];
let browser;
try {

	browser = await puppeteer.launch( {
		executablePath: args.chromium,
		headless: true,
		args: [ '--no-sandbox', '--use-angle=swiftshader', '--enable-unsafe-swiftshader', '--ignore-gpu-blocklist',
			`--window-size=${ width },${ height }`, '--hide-scrollbars', '--force-device-scale-factor=1' ],
	} );
	const page = await browser.newPage();
	await page.setViewport( { width, height, deviceScaleFactor: 1 } );
	page.on( 'console', m => {

		if ( m.type() === 'error' ) consoleErrors.push( m.text() );

	} );
	page.on( 'pageerror', e => consoleErrors.push( String( e ) ) );
	page.on( 'requestfailed', r => consoleErrors.push( `request failed: ${ r.url() }` ) );
	page.on( 'response', r => {

		if ( r.status() >= 400 ) consoleErrors.push( `HTTP ${ r.status() }: ${ r.url() }` );

	} );
	const start = Date.now();
	await page.goto( url, { waitUntil: 'load', timeout: timeoutMs } );
	try {

		// --wait first-frame: only until the first frame with terrain is drawn (the viewer's start-up time).
		const until = args.wait === 'first-frame' ? 'window.strataStats.firstFrameMs !== null' : 'window.strataReady === true';
		await page.waitForFunction( `${ until } || window.strataError !== undefined`, { timeout: timeoutMs, polling: 50 } );

	} catch {

		const partial = await page.evaluate( () => JSON.stringify( window.strataStats ) ).catch( () => 'none' );
		fail( `the viewer was not ready within ${ timeoutMs } ms (${ url }); stats so far: ${ partial }; console errors (${ consoleErrors.length }, the first 10): ${ JSON.stringify( consoleErrors.slice( 0, 10 ) ) }` );

	}
	const stats = await page.evaluate( () => ( { ...window.strataStats, error: window.strataError } ) );
	const canvas = await page.$( 'canvas' );
	if ( ! canvas ) fail( 'the page has no canvas' );
	await canvas.screenshot( { path: args.out, omitBackground: false } );
	console.log( JSON.stringify( { ok: ! stats.error, url, consoleErrors, stats, pageLoadMs: Date.now() - start } ) );

} catch ( e ) {

	fail( String( e && e.stack || e ) );

} finally {

	if ( browser ) await browser.close();
	server.close();

}
