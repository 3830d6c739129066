// SPDX-FileCopyrightText: The Strata authors
// SPDX-License-Identifier: MIT

// A PNG decoder for the maps `strata bake` writes (8 bits per channel,
// grey, grey + alpha, RGB or RGBA, not interlaced), to RGBA bytes exactly
// as stored: the browser's own image decoding may premultiply alpha or
// convert colour spaces, which would change a mask map's channels.

import { unzlibSync } from 'three/examples/jsm/libs/fflate.module.js';

const CHANNELS = { 0: 1, 2: 3, 4: 2, 6: 4 };

function paeth( a, b, c ) {

	const p = a + b - c;
	const pa = Math.abs( p - a ), pb = Math.abs( p - b ), pc = Math.abs( p - c );
	if ( pa <= pb && pa <= pc ) return a;
	return pb <= pc ? b : c;

}

/** Decodes `buffer` (an ArrayBuffer holding a PNG) to { width, height, data: Uint8Array RGBA, rows top first }. */
export function decodePng( buffer, name = 'PNG' ) {

	const bytes = new Uint8Array( buffer );
	const view = new DataView( buffer );
	const signature = [ 137, 80, 78, 71, 13, 10, 26, 10 ];
	if ( bytes.length < 8 || signature.some( ( v, i ) => bytes[ i ] !== v ) ) throw new Error( `${ name }: not a PNG file` );
	let offset = 8, width = 0, height = 0, colourType = -1;
	const idat = [];
	while ( offset + 8 <= bytes.length ) {

		const length = view.getUint32( offset );
		const type = String.fromCharCode( ...bytes.subarray( offset + 4, offset + 8 ) );
		const data = bytes.subarray( offset + 8, offset + 8 + length );
		if ( type === 'IHDR' ) {

			width = view.getUint32( offset + 8 );
			height = view.getUint32( offset + 12 );
			const depth = data[ 8 ];
			colourType = data[ 9 ];
			if ( depth !== 8 || ! ( colourType in CHANNELS ) || data[ 12 ] !== 0 ) {

				throw new Error( `${ name }: only 8-bit, non-interlaced grey/RGB(A) PNGs are supported (depth ${ depth }, colour type ${ colourType })` );

			}

		} else if ( type === 'IDAT' ) idat.push( data );
		else if ( type === 'IEND' ) break;
		offset += 12 + length;

	}
	const packed = new Uint8Array( idat.reduce( ( n, d ) => n + d.length, 0 ) );
	let at = 0;
	for ( const d of idat ) {

		packed.set( d, at );
		at += d.length;

	}
	const raw = unzlibSync( packed );
	const channels = CHANNELS[ colourType ];
	const stride = width * channels;
	if ( raw.length < height * ( stride + 1 ) ) throw new Error( `${ name }: truncated image data` );
	const pixels = new Uint8Array( height * stride );
	for ( let y = 0; y < height; y ++ ) {

		const filter = raw[ y * ( stride + 1 ) ];
		const src = y * ( stride + 1 ) + 1;
		const dst = y * stride;
		for ( let x = 0; x < stride; x ++ ) {

			const a = x >= channels ? pixels[ dst + x - channels ] : 0;
			const b = y > 0 ? pixels[ dst + x - stride ] : 0;
			const c = x >= channels && y > 0 ? pixels[ dst + x - stride - channels ] : 0;
			let v = raw[ src + x ];
			if ( filter === 1 ) v += a;
			else if ( filter === 2 ) v += b;
			else if ( filter === 3 ) v += ( a + b ) >> 1;
			else if ( filter === 4 ) v += paeth( a, b, c );
			else if ( filter !== 0 ) throw new Error( `${ name }: bad filter ${ filter } on row ${ y }` );
			pixels[ dst + x ] = v & 255;

		}

	}
	const data = new Uint8Array( width * height * 4 );
	for ( let i = 0, n = width * height; i < n; i ++ ) {

		const s = i * channels;
		if ( channels >= 3 ) {

			data[ 4 * i ] = pixels[ s ];
			data[ 4 * i + 1 ] = pixels[ s + 1 ];
			data[ 4 * i + 2 ] = pixels[ s + 2 ];
			data[ 4 * i + 3 ] = channels === 4 ? pixels[ s + 3 ] : 255;

		} else {

			data[ 4 * i ] = data[ 4 * i + 1 ] = data[ 4 * i + 2 ] = pixels[ s ];
			data[ 4 * i + 3 ] = channels === 2 ? pixels[ s + 1 ] : 255;

		}

	}
	return { width, height, data };

}
