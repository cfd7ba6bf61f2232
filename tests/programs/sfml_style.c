/* A program that makes the GLX and GL calls of an SFML 2 game (tests/end_to_end/sfml_style.rs).
 *
 * Like SFML's GlxContext: a hidden 1x1 window with a context of its own, then the game window
 * with a context sharing its objects, both created with glXCreateContextAttribsARB from the
 * first configuration of glXChooseFBConfig(dpy, screen, NULL) whose visual is the window's
 * visual; the window's visual is the best of XGetVisualInfo's list as glXGetConfig describes
 * it (double-buffered, 32 colour bits, no depth, stencil or samples). Each frame: a texture is
 * cleared to the frame's colour in a framebuffer object and copied to a second texture with
 * glBlitFramebufferEXT (sf::Texture::update), then the window is cleared and 1,500 small quads
 * are drawn with glDrawArrays from client arrays, moving with the frame, and the second texture
 * on a quad in the top-left 32x32 pixels, with glGetError after every call.
 *
 * Usage: sfml_style FRAMES. Every 10th frame, after glXSwapBuffers and XSync, the window is
 * read back with XGetImage and one line is printed:
 *     sample FRAME R G B SUM
 * R G B: the pixel at (8, 8), inside the textured quad; SUM: the sum of every pixel value of
 * the window. The colour of frame f is ((f * 5) % 256, (f * 11) % 256, 255 - (f * 3) % 256).
 * Exits 1 with a message on stderr when a step fails (and on the first GL error). */

#include <stdio.h>
#include <stdlib.h>
#include <string.h>
#include <X11/Xlib.h>
#include <X11/Xutil.h>
#include <GL/gl.h>
#include <GL/glx.h>
#include <GL/glext.h>

#define WIDTH 160
#define HEIGHT 120
#define QUADS 1500

static void fail(const char *what) {
    fprintf(stderr, "sfml_style: %s\n", what);
    exit(1);
}

static void check(const char *call) {
    GLenum e = glGetError();
    if (e != GL_NO_ERROR) {
        fprintf(stderr, "sfml_style: GL error 0x%04x after %s\n", e, call);
        exit(1);
    }
}

typedef GLXContext (*CreateContextAttribs)(Display *, GLXFBConfig, GLXContext, Bool, const int *);
static PFNGLGENFRAMEBUFFERSEXTPROC genFramebuffers;
static PFNGLBINDFRAMEBUFFEREXTPROC bindFramebuffer;
static PFNGLFRAMEBUFFERTEXTURE2DEXTPROC framebufferTexture2D;
static PFNGLCHECKFRAMEBUFFERSTATUSEXTPROC checkFramebufferStatus;
static PFNGLBLITFRAMEBUFFEREXTPROC blitFramebuffer;

static void *proc(const char *name) {
    void *p = (void *)glXGetProcAddressARB((const GLubyte *)name);
    if (!p)
        fail(name);
    return p;
}

/* SFML's GlxContext::selectBestVisual: the double-buffered visual whose colour, depth,
 * stencil and sample counts are nearest to 32, 0, 0 and 0. */
static XVisualInfo best_visual(Display *dpy, int screen) {
    XVisualInfo template;
    template.screen = screen;
    int count = 0;
    XVisualInfo *visuals = XGetVisualInfo(dpy, VisualScreenMask, &template, &count);
    int best = -1, best_score = 0x7fffffff;
    for (int i = 0; i < count; ++i) {
        int use_gl = 0, doubled = 0, r = 0, g = 0, b = 0, a = 0, depth = 0, stencil = 0, samples = 0;
        if (glXGetConfig(dpy, &visuals[i], GLX_USE_GL, &use_gl) != 0 || !use_gl)
            continue;
        glXGetConfig(dpy, &visuals[i], GLX_DOUBLEBUFFER, &doubled);
        if (!doubled)
            continue;
        glXGetConfig(dpy, &visuals[i], GLX_RED_SIZE, &r);
        glXGetConfig(dpy, &visuals[i], GLX_GREEN_SIZE, &g);
        glXGetConfig(dpy, &visuals[i], GLX_BLUE_SIZE, &b);
        glXGetConfig(dpy, &visuals[i], GLX_ALPHA_SIZE, &a);
        glXGetConfig(dpy, &visuals[i], GLX_DEPTH_SIZE, &depth);
        glXGetConfig(dpy, &visuals[i], GLX_STENCIL_SIZE, &stencil);
        glXGetConfig(dpy, &visuals[i], GLX_SAMPLES_ARB, &samples);
        int score = abs(r + g + b + a - 32) + depth + stencil + samples;
        if (score < best_score) {
            best = i;
            best_score = score;
        }
    }
    if (best < 0)
        fail("no double-buffered visual");
    XVisualInfo chosen = visuals[best];
    XFree(visuals);
    return chosen;
}

/* SFML's GlxContext::createContext: the first configuration of the whole list with the
 * window's visual, a context of version 1.2 in the compatibility profile. */
static GLXContext create_context(Display *dpy, int screen, VisualID visual, GLXContext share) {
    int count = 0;
    GLXFBConfig *configs = glXChooseFBConfig(dpy, screen, NULL, &count);
    GLXFBConfig *config = NULL;
    for (int i = 0; configs && i < count && !config; ++i) {
        XVisualInfo *v = glXGetVisualFromFBConfig(dpy, configs[i]);
        if (v && v->visualid == visual)
            config = &configs[i];
        if (v)
            XFree(v);
    }
    if (!config)
        fail("no configuration of the window's visual");
    CreateContextAttribs create = (CreateContextAttribs)proc("glXCreateContextAttribsARB");
    int attribs[] = {GLX_CONTEXT_MAJOR_VERSION_ARB, 1, GLX_CONTEXT_MINOR_VERSION_ARB, 2,
                     GLX_CONTEXT_PROFILE_MASK_ARB, GLX_CONTEXT_COMPATIBILITY_PROFILE_BIT_ARB, 0};
    GLXContext ctx = create(dpy, *config, share, True, attribs);
    XFree(configs);
    if (!ctx)
        fail("glXCreateContextAttribsARB");
    return ctx;
}

static Window create_window(Display *dpy, int screen, XVisualInfo *vis, int width, int height, int map) {
    XSetWindowAttributes attrs;
    memset(&attrs, 0, sizeof attrs);
    attrs.colormap = XCreateColormap(dpy, RootWindow(dpy, screen), vis->visual, AllocNone);
    attrs.border_pixel = 0;
    Window w = XCreateWindow(dpy, RootWindow(dpy, screen), 0, 0, width, height, 0, vis->depth, InputOutput,
                             vis->visual, CWColormap | CWBorderPixel, &attrs);
    if (map) {
        XMapWindow(dpy, w);
        XSync(dpy, False);
    }
    return w;
}

static void frame_colour(int f, GLubyte out[3]) {
    out[0] = (GLubyte)((f * 5) % 256);
    out[1] = (GLubyte)((f * 11) % 256);
    out[2] = (GLubyte)(255 - (f * 3) % 256);
}

/* The 8-bit value of a channel of pixel `p` under `mask`. */
static unsigned channel(unsigned long p, unsigned long mask) {
    int shift = 0;
    while (mask && !(mask & 1)) {
        mask >>= 1;
        p >>= 1;
        ++shift;
    }
    return (unsigned)((p & mask) * 255 / (mask ? mask : 1));
}

int main(int argc, char **argv) {
    int frames = argc > 1 ? atoi(argv[1]) : 300;
    Display *dpy = XOpenDisplay(NULL);
    if (!dpy)
        fail("cannot open the display");
    int screen = DefaultScreen(dpy);
    XVisualInfo vis = best_visual(dpy, screen);

    /* The hidden shared context (sf::GlContext's shared context) and a texture made in it. */
    Window hidden = create_window(dpy, screen, &vis, 1, 1, 0);
    GLXContext shared = create_context(dpy, screen, vis.visualid, NULL);
    if (!glXMakeCurrent(dpy, hidden, shared))
        fail("glXMakeCurrent on the hidden window");
    GLuint textures[2];
    glGenTextures(2, textures);
    check("glGenTextures");
    for (int i = 0; i < 2; ++i) {
        glBindTexture(GL_TEXTURE_2D, textures[i]);
        check("glBindTexture");
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
        check("glTexParameteri");
        glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
        check("glTexParameteri");
        glTexImage2D(GL_TEXTURE_2D, 0, GL_RGBA, 16, 16, 0, GL_RGBA, GL_UNSIGNED_BYTE, NULL);
        check("glTexImage2D");
    }
    glFlush();
    glXMakeCurrent(dpy, None, NULL);

    /* The game window with its own context sharing the first one's objects. */
    Window window = create_window(dpy, screen, &vis, WIDTH, HEIGHT, 1);
    GLXContext game = create_context(dpy, screen, vis.visualid, shared);
    glXMakeCurrent(dpy, None, NULL);
    if (!glXMakeCurrent(dpy, window, game))
        fail("glXMakeCurrent on the game window");
    genFramebuffers = (PFNGLGENFRAMEBUFFERSEXTPROC)proc("glGenFramebuffersEXT");
    bindFramebuffer = (PFNGLBINDFRAMEBUFFEREXTPROC)proc("glBindFramebufferEXT");
    framebufferTexture2D = (PFNGLFRAMEBUFFERTEXTURE2DEXTPROC)proc("glFramebufferTexture2DEXT");
    checkFramebufferStatus = (PFNGLCHECKFRAMEBUFFERSTATUSEXTPROC)proc("glCheckFramebufferStatusEXT");
    blitFramebuffer = (PFNGLBLITFRAMEBUFFEREXTPROC)proc("glBlitFramebufferEXT");
    GLuint fbos[2];
    genFramebuffers(2, fbos);
    check("glGenFramebuffersEXT");
    for (int i = 0; i < 2; ++i) {
        bindFramebuffer(GL_FRAMEBUFFER_EXT, fbos[i]);
        check("glBindFramebufferEXT");
        framebufferTexture2D(GL_FRAMEBUFFER_EXT, GL_COLOR_ATTACHMENT0_EXT, GL_TEXTURE_2D, textures[i], 0);
        check("glFramebufferTexture2DEXT");
        if (checkFramebufferStatus(GL_FRAMEBUFFER_EXT) != GL_FRAMEBUFFER_COMPLETE_EXT)
            fail("framebuffer object incomplete");
        check("glCheckFramebufferStatusEXT");
    }
    bindFramebuffer(GL_FRAMEBUFFER_EXT, 0);
    check("glBindFramebufferEXT");

    static GLfloat quads[QUADS * 4 * 2];
    static GLubyte colours[QUADS * 4 * 4];
    static const GLfloat corner[4][2] = {{0, 0}, {1, 0}, {1, 1}, {0, 1}};
    static const GLfloat sprite[4 * 2] = {0, 0, 32, 0, 32, 32, 0, 32};
    static const GLfloat sprite_uv[4 * 2] = {0, 0, 1, 0, 1, 1, 0, 1};
    for (int f = 0; f < frames; ++f) {
        GLubyte c[3];
        frame_colour(f, c);
        /* sf::RenderTexture clear, then sf::Texture::update(texture): a blit between FBOs. */
        bindFramebuffer(GL_FRAMEBUFFER_EXT, fbos[0]);
        check("glBindFramebufferEXT");
        glViewport(0, 0, 16, 16);
        check("glViewport");
        glClearColor(c[0] / 255.0f, c[1] / 255.0f, c[2] / 255.0f, 1);
        check("glClearColor");
        glClear(GL_COLOR_BUFFER_BIT);
        check("glClear");
        bindFramebuffer(GL_READ_FRAMEBUFFER_EXT, fbos[0]);
        check("glBindFramebufferEXT");
        bindFramebuffer(GL_DRAW_FRAMEBUFFER_EXT, fbos[1]);
        check("glBindFramebufferEXT");
        blitFramebuffer(0, 0, 16, 16, 0, 0, 16, 16, GL_COLOR_BUFFER_BIT, GL_NEAREST);
        check("glBlitFramebufferEXT");
        bindFramebuffer(GL_FRAMEBUFFER_EXT, 0);
        check("glBindFramebufferEXT");

        /* sf::RenderWindow: clear, 2D projection, one glDrawArrays per shape. */
        glViewport(0, 0, WIDTH, HEIGHT);
        check("glViewport");
        glClearColor(0, 0, 0.15f, 1);
        check("glClearColor");
        glClear(GL_COLOR_BUFFER_BIT);
        check("glClear");
        glMatrixMode(GL_PROJECTION);
        check("glMatrixMode");
        glLoadIdentity();
        check("glLoadIdentity");
        glOrtho(0, WIDTH, HEIGHT, 0, -1, 1);
        check("glOrtho");
        glMatrixMode(GL_MODELVIEW);
        check("glMatrixMode");
        glLoadIdentity();
        check("glLoadIdentity");
        for (int q = 0; q < QUADS; ++q) {
            float x = (float)((q * 7 + f * 2) % WIDTH), y = (float)(40 + (q * 13) % (HEIGHT - 40));
            for (int k = 0; k < 4; ++k) {
                quads[(q * 4 + k) * 2] = x + corner[k][0] * 2;
                quads[(q * 4 + k) * 2 + 1] = y + corner[k][1] * 2;
                colours[(q * 4 + k) * 4] = (GLubyte)(q * 3);
                colours[(q * 4 + k) * 4 + 1] = (GLubyte)(q * 5 + f);
                colours[(q * 4 + k) * 4 + 2] = 200;
                colours[(q * 4 + k) * 4 + 3] = 255;
            }
        }
        glEnableClientState(GL_VERTEX_ARRAY);
        check("glEnableClientState");
        glEnableClientState(GL_COLOR_ARRAY);
        check("glEnableClientState");
        glVertexPointer(2, GL_FLOAT, 0, quads);
        check("glVertexPointer");
        glColorPointer(4, GL_UNSIGNED_BYTE, 0, colours);
        check("glColorPointer");
        for (int q = 0; q < QUADS; ++q) {
            glDrawArrays(GL_TRIANGLE_FAN, q * 4, 4);
            check("glDrawArrays");
        }
        glDisableClientState(GL_COLOR_ARRAY);
        check("glDisableClientState");
        /* The copied texture as a sprite. */
        glColor4ub(255, 255, 255, 255);
        check("glColor4ub");
        glEnable(GL_TEXTURE_2D);
        check("glEnable");
        glBindTexture(GL_TEXTURE_2D, textures[1]);
        check("glBindTexture");
        glEnableClientState(GL_TEXTURE_COORD_ARRAY);
        check("glEnableClientState");
        glVertexPointer(2, GL_FLOAT, 0, sprite);
        check("glVertexPointer");
        glTexCoordPointer(2, GL_FLOAT, 0, sprite_uv);
        check("glTexCoordPointer");
        glDrawArrays(GL_TRIANGLE_FAN, 0, 4);
        check("glDrawArrays");
        glDisableClientState(GL_TEXTURE_COORD_ARRAY);
        check("glDisableClientState");
        glDisable(GL_TEXTURE_2D);
        check("glDisable");
        glXSwapBuffers(dpy, window);

        if (f % 10 == 9) {
            XSync(dpy, False);
            XImage *image = XGetImage(dpy, window, 0, 0, WIDTH, HEIGHT, AllPlanes, ZPixmap);
            if (!image)
                fail("XGetImage");
            unsigned long sum = 0;
            for (int y = 0; y < HEIGHT; ++y)
                for (int x = 0; x < WIDTH; ++x) {
                    unsigned long p = XGetPixel(image, x, y);
                    sum += channel(p, vis.red_mask) + channel(p, vis.green_mask) + channel(p, vis.blue_mask);
                }
            unsigned long p = XGetPixel(image, 8, 8);
            printf("sample %d %u %u %u %lu\n", f, channel(p, vis.red_mask), channel(p, vis.green_mask),
                   channel(p, vis.blue_mask), sum);
            fflush(stdout);
            XDestroyImage(image);
        }
    }
    glXMakeCurrent(dpy, None, NULL);
    glXDestroyContext(dpy, game);
    glXDestroyContext(dpy, shared);
    XCloseDisplay(dpy);
    return 0;
}
