/* A Windows OpenGL 1.1 program for the Wine test (tests/end_to_end/wine.rs): a WGL window,
 * a display list, a texture, lighting off, an immediate-mode triangle over a cleared
 * background, then glReadPixels of two pixels printed as "center R G B" and "corner R G B",
 * over FRAMES frames (argument 1, default 3) with SwapBuffers between them.
 * Build: x86_64-w64-mingw32-gcc -O2 -o wgl_triangle.exe wgl_triangle.c -lopengl32 -lgdi32 */
#include <windows.h>
#include <GL/gl.h>
#include <stdio.h>
#include <stdlib.h>

static LRESULT CALLBACK window_proc(HWND hwnd, UINT msg, WPARAM w, LPARAM l) {
    return DefWindowProcA(hwnd, msg, w, l);
}

int main(int argc, char **argv) {
    int frames = argc > 1 ? atoi(argv[1]) : 3;
    WNDCLASSA wc = {0};
    wc.style = CS_OWNDC;
    wc.lpfnWndProc = window_proc;
    wc.hInstance = GetModuleHandleA(NULL);
    wc.lpszClassName = "glrt_wgl";
    RegisterClassA(&wc);
    HWND hwnd = CreateWindowA("glrt_wgl", "glrt WGL triangle", WS_OVERLAPPEDWINDOW | WS_VISIBLE,
                              0, 0, 160, 120, NULL, NULL, wc.hInstance, NULL);
    HDC dc = GetDC(hwnd);
    PIXELFORMATDESCRIPTOR pfd = {0};
    pfd.nSize = sizeof pfd;
    pfd.nVersion = 1;
    pfd.dwFlags = PFD_DRAW_TO_WINDOW | PFD_SUPPORT_OPENGL | PFD_DOUBLEBUFFER;
    pfd.iPixelType = PFD_TYPE_RGBA;
    pfd.cColorBits = 24;
    pfd.cDepthBits = 16;
    int format = ChoosePixelFormat(dc, &pfd);
    if (!format || !SetPixelFormat(dc, format, &pfd)) {
        printf("no pixel format\n");
        return 2;
    }
    HGLRC rc = wglCreateContext(dc);
    if (!rc || !wglMakeCurrent(dc, rc)) {
        printf("no context\n");
        return 2;
    }
    printf("renderer %s\n", (const char *)glGetString(GL_RENDERER));
    RECT client;
    GetClientRect(hwnd, &client);
    int width = client.right, height = client.bottom;

    unsigned char texels[2 * 2 * 3] = {255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255, 255};
    GLuint texture;
    glGenTextures(1, &texture);
    glBindTexture(GL_TEXTURE_2D, texture);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MIN_FILTER, GL_NEAREST);
    glTexParameteri(GL_TEXTURE_2D, GL_TEXTURE_MAG_FILTER, GL_NEAREST);
    glTexImage2D(GL_TEXTURE_2D, 0, GL_RGB, 2, 2, 0, GL_RGB, GL_UNSIGNED_BYTE, texels);

    GLuint list = glGenLists(1);
    glNewList(list, GL_COMPILE);
    glEnable(GL_TEXTURE_2D);
    glBegin(GL_TRIANGLES);
    glColor3f(1.0f, 0.5f, 0.0f);
    glTexCoord2f(0, 0); glVertex2f(-0.9f, -0.9f);
    glTexCoord2f(1, 0); glVertex2f(0.9f, -0.9f);
    glTexCoord2f(0, 1); glVertex2f(0.0f, 0.9f);
    glEnd();
    glDisable(GL_TEXTURE_2D);
    glEndList();

    unsigned char center[4] = {0}, corner[4] = {0};
    for (int frame = 0; frame < frames; frame++) {
        MSG msg;
        while (PeekMessageA(&msg, NULL, 0, 0, PM_REMOVE)) DispatchMessageA(&msg);
        glViewport(0, 0, width, height);
        glClearColor(0.0f, 0.0f, 1.0f, 1.0f);
        glClear(GL_COLOR_BUFFER_BIT | GL_DEPTH_BUFFER_BIT);
        glCallList(list);
        glFinish();
        glReadPixels(width / 2, height / 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, center);
        glReadPixels(1, height - 2, 1, 1, GL_RGBA, GL_UNSIGNED_BYTE, corner);
        SwapBuffers(dc);
    }
    printf("size %d %d\n", width, height);
    printf("center %d %d %d\n", center[0], center[1], center[2]);
    printf("corner %d %d %d\n", corner[0], corner[1], corner[2]);
    fflush(stdout);
    wglMakeCurrent(NULL, NULL);
    wglDeleteContext(rc);
    ReleaseDC(hwnd, dc);
    DestroyWindow(hwnd);
    return 0;
}
