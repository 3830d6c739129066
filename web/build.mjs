// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// Bundles the viewer (src/main.js, three.js, 3d-tiles-renderer and the
// generated shaders) into one script with esbuild, so the page needs no
// network, and copies index.html beside it. Run by web/CMakeLists.txt:
//   node build.mjs --modules <node_modules from npm ci> --shaders <strata-shaders.js> --out <dir>

import { copyFileSync, existsSync, mkdirSync, readFileSync, readdirSync, writeFileSync } from 'node:fs';
import { dirname, join, resolve } from 'node:path';
import { fileURLToPath, pathToFileURL } from 'node:url';

const args = {};
for ( let i = 2; i < process.argv.length; i += 2 ) args[ process.argv[ i ].replace( /^--/, '' ) ] = process.argv[ i + 1 ];
for ( const key of [ 'modules', 'shaders', 'out' ] ) {

	if ( ! args[ key ] ) {

		console.error( `build.mjs: --${ key } is missing` );
		process.exit( 2 );

	}

}
const here = dirname( fileURLToPath( import.meta.url ) );
const esbuild = await import( pathToFileURL( join( resolve( args.modules ), 'esbuild', 'lib', 'main.js' ) ).href );
const shaders = resolve( args.shaders );
mkdirSync( args.out, { recursive: true } );
const result = await esbuild.build( {
	metafile: true,
	entryPoints: [ join( here, 'src', 'main.js' ) ],
	bundle: true,
	format: 'iife',
	target: 'es2020',
	minify: true,
	legalComments: 'eof', // the bundled packages' licence notices stay in viewer.js
	outfile: join( args.out, 'viewer.js' ),
	nodePaths: [ resolve( args.modules ) ],
	logLevel: 'warning',
	plugins: [ {
		name: 'strata-shaders',
		setup( build ) {

			build.onResolve( { filter: /^strata:shaders$/ }, () => ( { path: shaders } ) );

		},
	} ],
} );
copyFileSync( join( here, 'index.html' ), join( args.out, 'index.html' ) );

// The licences of the npm packages bundled into viewer.js, in one file
// beside it (three.js' notice is also in the bundle; 3d-tiles-renderer,
// Apache-2.0, has none in its sources).
const packages = new Set();
for ( const output of Object.values( result.metafile.outputs ) ) for ( const [ input, use ] of Object.entries( output.inputs ) ) {

	if ( use.bytesInOutput === 0 ) continue; // parsed but shaken out

	const m = /node_modules\/((?:@[^/]+\/)?[^/]+)\//.exec( input );
	if ( m ) packages.add( m[ 1 ] );

}
let notices = 'Third-party software bundled into viewer.js (from npm, pinned by web/package-lock.json).\n';
for ( const name of [ ...packages ].sort() ) {

	const dir = join( resolve( args.modules ), name );
	const meta = JSON.parse( readFileSync( join( dir, 'package.json' ), 'utf8' ) );
	const licence = existsSync( dir ) ? readdirSync( dir ).find( f => /^(licen[cs]e|copying)/i.test( f ) ) : undefined;
	notices += `\n==== ${ name } ${ meta.version } (${ meta.license }) ====\n\n`;
	notices += licence ? readFileSync( join( dir, licence ), 'utf8' ) : `(no licence file in the package; licence: ${ meta.license })\n`;

}
writeFileSync( join( args.out, 'THIRD_PARTY_LICENSES.txt' ), notices );
