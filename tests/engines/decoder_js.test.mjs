// decoders/baker_irradiance.js against decoders/baker_irradiance.h: for every basis, the
// irradiance and visibility the header decodes from random coefficients (decoder_samples) agree
// within 1e-5 of the coefficients' magnitude (≤ 1).
// argv: node decoder_js.test.mjs DECODER_SAMPLES SOURCE_DIR
import { execFileSync } from 'node:child_process';
import path from 'node:path';
import { pathToFileURL } from 'node:url';

const [ samplesBinary, sourceDir ] = process.argv.slice( 2 );
const { BasisDecoder } = await import( pathToFileURL( path.join( sourceDir, 'decoders/baker_irradiance.js' ) ) );
const bases = JSON.parse( execFileSync( samplesBinary, { encoding: 'utf8', maxBuffer: 1 << 28 } ) );
let checks = 0, failures = 0, worst = 0;
for ( const entry of bases ) {
	const decoder = new BasisDecoder( entry.basis, entry.sharpness ?? 0 );
	if ( entry.axes ) decoder.setLobeAxes( entry.axes );
	++ checks;
	if ( ! decoder.valid || decoder.coefficientsPerProbe !== entry.coefficients_per_probe ) {
		++ failures;
		console.error( `FAIL: ${ entry.basis }: valid ${ decoder.valid }, ${ decoder.coefficientsPerProbe } coefficients per probe` );
		continue;
	}
	for ( const c of entry.cases ) {
		const got = [ ...decoder.irradiance( c.coefficients, c.direction ), decoder.visibility( c.coefficients, c.direction ) ];
		const expected = [ ...c.irradiance, c.visibility ];
		for ( let k = 0; k < 4; ++ k ) {
			const error = Math.abs( got[ k ] - expected[ k ] );
			worst = Math.max( worst, error );
			++ checks;
			if ( ! ( error <= 1e-5 ) ) {
				if ( ++ failures <= 20 ) console.error( `FAIL: ${ entry.basis } at ${ c.direction }: value ${ k } ${ got[ k ] }, header ${ expected[ k ] }` );
			}
		}
	}
}
console.log( `${ bases.length } bases; largest difference from the header ${ worst.toExponential( 2 ) }` );
console.log( `decoder_js: ${ checks - failures } of ${ checks } checks passed` );
process.exit( failures === 0 && bases.length > 0 ? 0 : 1 );
